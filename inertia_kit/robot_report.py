"""`inertia-kit report`: a table of a robot's links and their declared mass properties."""

from __future__ import annotations

import json
from typing import Any

from inertia_kit import model
from inertia_kit.analysis import declared, geometry_summary
from inertia_kit.text import fmt


def link_rows(robot: model.Robot) -> list[dict[str, Any]]:
    """One record per link, in document order, with JSON-ready values (SI units)."""
    rows = []
    for link in robot.links:
        joint = robot.parent_joint(link.name)
        properties = declared(link)
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
                "inertial": "none"
                if link.inertial is None
                else ("complete" if properties else "incomplete"),
                "geometry": geometry_summary(link),
                "file": source.path,
                "line": source.line,
                "call_site": None
                if not source.calls
                else {"file": source.calls[0].path, "line": source.calls[0].line},
            }
        )
    return rows


def total_mass(rows: list[dict[str, Any]]) -> float:
    return sum(row["mass"] for row in rows if row["mass"] is not None)


def render(robot: model.Robot, output_format: str = "text") -> str:
    """The report as ``text`` (aligned columns), ``markdown`` or ``json``."""
    rows = link_rows(robot)
    if output_format == "json":
        return json.dumps(
            {
                "robot": robot.name,
                "files": list(robot.files),
                "links": rows,
                "total_mass": total_mass(rows),
            },
            indent=2,
        )
    header = [
        "link",
        "joint (type)",
        "mass kg",
        "COM m",
        "principal moments kg·m²",
        "geometry",
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
                "-" if row["mass"] is None else fmt(row["mass"], 6),
                "-" if row["com"] is None else "(" + ", ".join(fmt(x, 4) for x in row["com"]) + ")",
                ("-" if row["inertial"] == "none" else row["inertial"])
                if row["principal_moments"] is None
                else ", ".join(fmt(x, 4) for x in row["principal_moments"]),
                row["geometry"],
                where,
            ]
        )
    name = robot.name or "unnamed robot"
    footer = f"total mass: {fmt(total_mass(rows), 6)} kg over {len(rows)} links ({name})"
    if output_format == "markdown":
        lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
        lines += [
            "| " + " | ".join(cell.replace("|", "\\|") for cell in r) + " |" for r in table[1:]
        ]
        return "\n".join([*lines, "", f"**{footer}**"])
    widths = [max(len(r[i]) for r in table) for i in range(len(header))]
    lines = [
        "  ".join(cell.ljust(w) for cell, w in zip(r, widths, strict=True)).rstrip() for r in table
    ]
    lines.insert(1, "  ".join("-" * w for w in widths))
    return "\n".join([*lines, footer])
