"""`inertia-kit report`: a table of a robot's links and their declared mass properties."""

from __future__ import annotations

import json
from typing import TYPE_CHECKING, Any

from inertia_kit.analysis.declared import declared
from inertia_kit.analysis.describe import geometry_summary
from inertia_kit.description import model
from inertia_kit.physics.formatting import fmt, tensor_text, vector_text
from inertia_kit.printable import printable

if TYPE_CHECKING:
    from inertia_kit.description.redaction import Redaction


def link_rows(robot: model.Robot) -> list[dict[str, Any]]:
    """
    One record per link, in document order, with JSON-ready values (SI units). A body whose
    mass properties its format's engine infers (MJCF without ``<inertial>``, or every body under
    ``inertiafromgeom="true"``) has the values MuJoCo compiles for it, ``inertial`` saying
    ``inferred``.
    """
    inferred = _inferred(robot)
    rows = []
    for link in robot.links:
        joint = robot.parent_joint(link.name)
        properties = inferred.get(link.name) or declared(link)
        source = link.source
        rows.append(
            {
                "link": link.name,
                "parent_joint": None if joint is None else joint.name,
                "joint_type": None if joint is None else joint.type,
                "mass": None if properties is None else properties.mass,
                "com": None if properties is None else properties.com.tolist(),
                "principal_moments": None
                if properties is None
                else properties.principal_moments.tolist(),
                "inertial": "inferred"
                if link.name in inferred
                else _state(link.inertial, properties),
                "geometry": geometry_summary(link),
                "meshes": _meshes(link),
                "file": source.path,
                "line": source.line,
                "call_site": None
                if source.call_site is source
                else {"file": source.call_site.path, "line": source.call_site.line},
            }
        )
    return rows


def _inferred(robot: model.Robot) -> dict[str, Any]:
    """The mass properties the engine infers for the bodies it infers, by name."""
    if robot.inference is None:
        return {}
    from inertia_kit.analysis.links import analyse
    from inertia_kit.engines.mujoco_inference import compiled

    found = {}
    for name, body in compiled(analyse(robot)).items():
        values = body.mass_properties
        if body.inferred and values is not None and values.mass > 0:
            found[name] = values
    return found


def _meshes(link: model.Link) -> list[dict[str, Any]]:
    """The link's meshes: URI, resolved file, the package resolution rule that found it."""
    return [
        {
            "kind": shape.kind,
            "filename": shape.geometry.filename,
            "path": shape.geometry.path,
            "rule": shape.geometry.rule,
            "problem": shape.geometry.problem,
            **({"searched": list(shape.geometry.searched)} if shape.geometry.path is None else {}),
        }
        for shape in (*link.collisions, *link.visuals)
        if isinstance(shape.geometry, model.Mesh)
    ]


def _found_by(meshes: list[dict[str, Any]]) -> str:
    """The report's ``mesh found by`` cell: each rule once, in order; ``not found``; ``-``."""
    rules = dict.fromkeys(m["rule"] or "not found" for m in meshes)
    return ", ".join(rules) or "-"


def _state(inertial: model.Inertial | None, properties: object) -> str:
    """``none``, ``complete``, ``invalid`` (a value not usable, IN004) or ``incomplete``."""
    if inertial is None:
        return "none"
    if properties is not None:
        return "complete"
    values = (inertial.mass, *inertial.tensor_values().values(), *vars(inertial.origin).values())
    return "invalid" if any(isinstance(v, model.Invalid) for v in values) else "incomplete"


def total_mass(rows: list[dict[str, Any]]) -> float:
    return sum(row["mass"] for row in rows if row["mass"] is not None)


def render(
    robot: model.Robot, output_format: str = "text", redaction: Redaction | None = None
) -> str:
    """
    The report as ``text`` (aligned columns), ``markdown`` or ``json``. Names, paths and values
    from the files are escaped in the text formats (:func:`~inertia_kit.printable.printable`);
    ``redaction`` (``--redact-env``) keeps values out of the JSON and out of each table cell
    before the columns are aligned (the rest of a text format is redacted by the caller).
    """
    rows = link_rows(robot)
    if output_format == "json":
        payload = {
            "robot": robot.name,
            "files": list(robot.files),
            "links": rows,
            "total_mass": total_mass(rows),
        }
        return json.dumps(payload if redaction is None else redaction.apply(payload), indent=2)
    header = [
        "link",
        "joint (type)",
        "mass kg",
        "COM m",
        "principal moments kg·m²",
        "geometry",
        "mesh found by",
        "source",
    ]
    table = [header]
    for row in rows:
        where = f"{row['file']}:{row['line']}"
        if row["call_site"]:
            where += f" via {row['call_site']['file']}:{row['call_site']['line']}"
        table.append(
            [
                row["link"],
                "(root)"
                if row["parent_joint"] is None
                else f"{row['parent_joint']} ({row['joint_type']})",
                "-"
                if row["mass"] is None
                else fmt(row["mass"], 6) + (" inferred" if row["inertial"] == "inferred" else ""),
                "-" if row["com"] is None else vector_text(row["com"]),
                ("-" if row["inertial"] == "none" else row["inertial"])
                if row["principal_moments"] is None
                else ", ".join(fmt(x, 4) for x in row["principal_moments"]),
                row["geometry"],
                _found_by(row["meshes"]),
                where,
            ]
        )
    name = robot.name or "unnamed robot"
    footer = printable(f"total mass: {fmt(total_mass(rows), 6)} kg over {len(rows)} links ({name})")
    table = _redacted(table, redaction)
    if output_format == "markdown":
        return "\n".join([*_markdown_table(table), "", f"**{footer}**"])
    return "\n".join([*_text_table(table), footer])


def _redacted(table: list[list[str]], redaction: Redaction | None) -> list[list[str]]:
    """``table`` with the values kept out cell by cell, before the columns are aligned (the
    caller's redaction of the whole text would leave them misaligned)."""
    if redaction is None:
        return table
    return [[redaction.text(cell) for cell in row] for row in table]


def _markdown_table(table: list[list[str]]) -> list[str]:
    """The rows of ``table`` (the first is the header) as a Markdown table."""
    table = [[printable(cell) for cell in row] for row in table]
    return [
        "| " + " | ".join(table[0]) + " |",
        "|" + "---|" * len(table[0]),
        *("| " + " | ".join(cell.replace("|", "\\|") for cell in r) + " |" for r in table[1:]),
    ]


def _text_table(table: list[list[str]]) -> list[str]:
    """The rows of ``table`` (the first is the header) in aligned columns, the header ruled."""
    table = [[printable(cell) for cell in row] for row in table]
    widths = [max(len(r[i]) for r in table) for i in range(len(table[0]))]
    lines = [
        "  ".join(cell.ljust(w) for cell, w in zip(r, widths, strict=True)).rstrip() for r in table
    ]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return lines


# --- inertia-kit report --lumped ------------------------------------------------------------


def lumped_records(robot: model.Robot, engines: tuple[str, ...]) -> list[dict[str, Any]]:
    """
    Per engine, the bodies it simulates (see :mod:`~.engines.lumping`): their links, joint,
    combined declared mass, COM, tensor (in the body link's frame) and principal moments; and
    the links it drops. JSON-ready, SI units.
    """
    from inertia_kit.analysis.links import analyse
    from inertia_kit.engines.lumping import simulated_bodies

    analysis = analyse(robot)
    records = []
    for engine in engines:
        found = simulated_bodies(analysis, engine)
        bodies = []
        for body in found.bodies:
            properties = body.mass_properties
            bodies.append(
                {
                    "body": body.name,
                    "links": list(body.links),
                    "joint": body.joint,
                    "static": body.static,
                    "mass": None if properties is None else properties.mass,
                    "com": None if properties is None else properties.com.tolist(),
                    "inertia": None if properties is None else properties.inertia.tolist(),
                    "principal_moments": None
                    if properties is None
                    else properties.principal_moments.tolist(),
                    "collisions": list(body.collisions),
                    "note": body.note,
                }
            )
        records.append(
            {
                "engine": engine,
                "bodies": bodies,
                "dropped": [
                    {"link": d.link, "joint": d.joint, "cause": d.cause, "reason": d.reason}
                    for d in found.dropped
                ],
            }
        )
    return records


_REASONS = {
    "no-inertial": "no <inertial>",
    "non-positive-mass": "mass ≤ 0",
    "ancestor": "below a dropped link",
}


def render_lumped(
    robot: model.Robot,
    engines: tuple[str, ...],
    output_format: str = "text",
    redaction: Redaction | None = None,
) -> str:
    """
    ``report --lumped``: per engine, a table of its bodies, then the dropped links;
    ``redaction`` as for :func:`render`.
    """
    from inertia_kit.engines.vocabulary import TITLES

    records = lumped_records(robot, engines)
    if output_format == "json":
        payload = {"robot": robot.name, "files": list(robot.files), "engines": records}
        return json.dumps(payload if redaction is None else redaction.apply(payload), indent=2)
    header = ["body", "links", "joint", "mass kg", "COM m", "inertia kg·m²", "principal kg·m²"]
    out: list[str] = []
    for record in records:
        title = TITLES.get(record["engine"], record["engine"])
        table = [header]
        for body in record["bodies"]:
            tensor = body["inertia"]
            table.append(
                [
                    body["body"] + (" (static)" if body["static"] else ""),
                    ", ".join(body["links"]),
                    body["joint"] or "-",
                    "-" if body["mass"] is None else fmt(body["mass"], 6),
                    "-" if body["com"] is None else vector_text(body["com"]),
                    "-" if tensor is None else tensor_text(tensor, separator="="),
                    "-"
                    if body["principal_moments"] is None
                    else ", ".join(fmt(x, 4) for x in body["principal_moments"]),
                ]
            )
        table = _redacted(table, redaction)
        notes = [f"{b['body']}: {b['note']}" for b in record["bodies"] if b["note"]]
        dropped = [
            f"{d['link']}"
            + (f" (joint {d['joint']})" if d["joint"] else "")
            + f": {_REASONS.get(d['reason'], d['reason'])}"
            + (f" `{d['cause']}`" if d["reason"] == "ancestor" else "")
            for d in record["dropped"]
        ]
        summary = (
            f"{len(record['bodies'])} bodies from {sum(len(b['links']) for b in record['bodies'])}"
            f" links, {len(record['dropped'])} dropped"
        )
        if output_format == "markdown":
            lines = [f"## {title}", "", *_markdown_table(table), "", f"**{summary}**"]
            lines += [printable(f"- note: {n}") for n in notes]
            lines += [printable(f"- dropped: {d}") for d in dropped]
            out.append("\n".join(lines))
            continue
        lines = [f"{title}:", *_text_table(table), summary]
        lines += [printable(f"note: {n}") for n in notes]
        lines += [printable(f"dropped: {d}") for d in dropped]
        out.append("\n".join(lines))
    return "\n\n".join(out)
