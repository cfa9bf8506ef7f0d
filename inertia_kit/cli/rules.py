"""``inertia-kit rules``: every rule of the catalogue, as ruff's ``ruff rule --all`` lists them."""

from __future__ import annotations

import json
from types import ModuleType

import click

from inertia_kit.cli.guard import GuardedCommand

COLUMNS = ("code", "name", "severity", "fix", "engine", "formats")


def rule_row(rule: ModuleType) -> dict[str, str | None]:
    """What the listing says of ``rule``: code, name, default severity, fix safety, engine,
    the description formats it judges."""
    from inertia_kit.lint import catalog

    return {
        "code": rule.CODE,
        "name": rule.NAME,
        "severity": str(rule.SEVERITY),
        "fix": catalog.fix_safety_text(rule),
        "engine": catalog.engine(rule),
        "formats": ",".join(catalog.formats(rule)),
    }


def _text(rows: list[dict[str, str | None]]) -> str:
    cells = [[row[c] or "-" for c in COLUMNS] for row in rows]
    widths = [max(len(c), *(len(r[i]) for r in cells)) for i, c in enumerate(COLUMNS)]
    lines = [list(COLUMNS), *cells]
    return "\n".join(
        "  ".join(cell.ljust(width) for cell, width in zip(line, widths, strict=True)).rstrip()
        for line in lines
    )


@click.command("rules", cls=GuardedCommand)
@click.option(
    "--output-format",
    type=click.Choice(["text", "json"]),
    default="text",
    show_default=True,
)
def rules_command(output_format: str) -> None:
    """Every rule: code, name, default severity, its fix (safe, unsafe or none; safe/unsafe:
    safe for an exact fit, unsafe for a real part's likely slip), the engine it needs (an
    engine rule runs only with --engine NAME; - for the others) and the description formats it
    judges (urdf, mjcf)."""
    from inertia_kit.lint import catalog

    rows = [rule_row(rule) for rule in catalog.RULES]
    if output_format == "json":
        click.echo(json.dumps(rows, indent=2))
    else:
        click.echo(_text(rows))
