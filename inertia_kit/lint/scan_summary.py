"""
What a scan's record says in sum (:func:`summarise`), and the keep-list a pipeline takes
(:func:`write_keep_list`), both read from the record one line at a time: counts only, so that
memory stays flat in the number of assets (a resumed run summarises every asset recorded).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path
from typing import Any

from inertia_kit.lint.findings import Severity

#: the statuses of an asset that was linted; the others count as errors for the exit code
LINTED = ("ok", "findings")
#: ``--keep-at``: the worst finding an asset kept may have (``none``: no finding at all)
KEEP_AT = ("none", "info", "warning", "error")


def worst(record: Mapping[str, Any]) -> Severity | None:
    """The highest severity among a record's findings, ``None`` without findings."""
    found = [Severity.parse(f["severity"]) for f in record.get("findings") or ()]
    return max(found, default=None)


def summarise(records: Iterable[Mapping[str, Any]], fail_on: Severity) -> dict[str, Any]:
    """
    Counts over ``records`` (a scan's lines): assets by status, findings by severity and by
    rule (code → name and count per severity), per top-level folder (assets, findings,
    statuses), the seconds of wall and CPU time the assets took, and ``failing``: the assets
    with a finding at or above ``fail_on`` or not linted (unreadable, over a limit, crashed).
    """
    statuses: Counter[str] = Counter()
    severities: Counter[str] = Counter()
    rules: dict[str, dict[str, Any]] = {}
    folders: dict[str, dict[str, Any]] = {}
    assets = failing = 0
    wall = cpu = 0.0
    for record in records:
        assets += 1
        status = record.get("status", "crashed")
        statuses[status] += 1
        folder = folders.setdefault(
            str(record.get("folder")), {"assets": 0, "findings": 0, "statuses": Counter()}
        )
        folder["assets"] += 1
        folder["statuses"][status] += 1
        for finding in record.get("findings") or ():
            severity = finding["severity"]
            severities[severity] += 1
            rule = rules.setdefault(finding["code"], {"name": finding["name"]})
            rule[severity] = rule.get(severity, 0) + 1
            folder["findings"] += 1
        highest = worst(record)
        if status not in LINTED or (highest is not None and highest >= fail_on):
            failing += 1
        wall += record.get("wall_seconds") or 0.0
        cpu += record.get("cpu_seconds") or 0.0
    return {
        "assets": assets,
        "statuses": {status: statuses[status] for status in sorted(statuses)},
        "findings": sum(severities.values()),
        "severities": {str(s): severities[str(s)] for s in sorted(Severity, reverse=True)},
        "rules": {code: rules[code] for code in sorted(rules)},
        "folders": {
            name: {**counts, "statuses": dict(sorted(counts["statuses"].items()))}
            for name, counts in sorted(folders.items())
        },
        "asset_seconds": round(wall, 3),
        "cpu_seconds": round(cpu, 3),
        "fail_on": str(fail_on),
        "failing": failing,
    }


def render(summary: Mapping[str, Any], folders_shown: int = 10) -> str:
    """The summary as text for stderr; the folders with the most findings first."""
    lines = [
        f"Scanned {summary['assets']} assets: "
        + ", ".join(f"{n} {status}" for status, n in summary["statuses"].items())
    ]
    run = summary.get("run")
    if run:
        lines.append(
            f"This run: {run['assets']} assets in {run['seconds']:.1f} s "
            f"({run['assets_per_second']:.1f} assets/s, {run['jobs']} workers)"
        )
    severities = ", ".join(f"{n} {s}" for s, n in summary["severities"].items())
    lines.append(f"Findings: {summary['findings']} ({severities})")
    for code, rule in summary["rules"].items():
        counts = ", ".join(f"{rule[s]} {s}" for s in summary["severities"] if s in rule)
        lines.append(f"  {code} {rule['name']}: {counts}")
    folders = sorted(summary["folders"].items(), key=lambda item: (-item[1]["findings"], item[0]))
    if folders:
        lines.append(f"Folders: {len(folders)}" + (", most findings first:" if folders else ""))
    for name, counts in folders[:folders_shown]:
        lines.append(f"  {name}: {counts['assets']} assets, {counts['findings']} findings")
    if len(folders) > folders_shown:
        lines.append(f"  ... {len(folders) - folders_shown} more (--summary FILE has them all)")
    return "\n".join(lines) + "\n"


def keeps(record: Mapping[str, Any], keep_at: str) -> bool:
    """Whether an asset goes on the keep-list: linted, its worst finding at most ``keep_at``."""
    if record.get("status") not in LINTED:
        return False
    highest = worst(record)
    if highest is None:
        return True
    return keep_at != "none" and highest <= Severity.parse(keep_at)


def write_keep_list(records: Iterable[Mapping[str, Any]], keep_at: str, path: str | Path) -> int:
    """Write the paths of the assets :func:`keeps`, one a line, in record order, replacing
    ``path`` at the end (a reader never sees half a list: the writer of every output,
    :func:`~inertia_kit.description.edits.write_atomic`, which also writes into a device or
    a named pipe rather than over it); how many."""
    from inertia_kit.description.edits import write_atomic

    kept = 0

    def lines() -> Iterator[bytes]:
        nonlocal kept
        for record in records:
            if keeps(record, keep_at):
                kept += 1
                yield (record["path"] + "\n").encode("utf-8", "surrogateescape")

    # a link at ``path`` is replaced, never written through (a planted one must not redirect it)
    write_atomic(path, lines(), create=True, follow_symlinks=False)
    return kept
