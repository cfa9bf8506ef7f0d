"""IN004 invalid-number: a numeric attribute whose text is not a finite number."""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from dataclasses import dataclass

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, FixRule, Repairs, Safety, Severity
from inertia_kit.lint.rules import RuleContext
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.numbers import unusable

CODE = "IN004"
NAME = "invalid-number"
SEVERITY = Severity.ERROR
SCOPE = "robot"
FIX = FixRule(
    "geometry", Safety.UNSAFE, Repairs.IMPOSSIBLE, "replace the <inertial> with its geometry's"
)
SUMMARY = (
    "a numeric attribute is not a number mass properties can be computed from (`abc`, `nan`, "
    "`inf`, `1,5`, `2kg`, `1e308`, `1e-320`)"
)

# a number as URDF writes it (urdfdom reads it): digits, a dot, an exponent
_PLAIN = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
# what C's strtod (which PyBullet's URDF reader uses) takes from the start of a text
_STRTOD = re.compile(
    r"\s*[+-]?(?:inf(?:inity)?|nan|(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)", re.IGNORECASE
)


def strtod(text: str) -> float:
    """The number strtod reads from the start of ``text`` (0 when none), as PyBullet does."""
    match = _STRTOD.match(text)
    if match is None:
        return 0.0
    try:
        return float(match.group(0))
    except (ValueError, OverflowError):
        return 0.0


def pybullet_reading(invalid: model.Invalid, vector: bool) -> str:
    """What PyBullet silently makes of the text: it never refuses a number."""
    if not vector:
        return fmt(strtod(invalid.text))
    pieces = invalid.text.split()
    if len(pieces) < 3:
        return '0 0 0 ("Couldn\'t parse vector3")'
    return " ".join(fmt(strtod(p)) for p in pieces[:3])


@dataclass(frozen=True)
class Place:
    """Where an invalid value sits: ``<mass value>`` of link `arm`."""

    element: str  # "<mass value>"
    link: str | None = None
    joint: str | None = None
    vector: bool = False

    @property
    def owner(self) -> str:
        if self.link is not None:
            return f"link `{self.link}`"
        if self.joint is not None:
            return f"joint `{self.joint}`"
        return "the robot"


def _places(robot: model.Robot) -> dict[int, Place]:
    """Every ``Invalid`` the model holds, by identity, with the element and owner it sits in."""
    found: dict[int, Place] = {}

    def note(value: object, element: str, *, link=None, joint=None, vector=False) -> None:
        if isinstance(value, model.Invalid):
            found[id(value)] = Place(f"<{element} {value.attribute}>", link, joint, vector)

    def origin(value: model.Origin, parent: str, **owner) -> None:
        note(value.xyz, f"{parent}><origin", vector=True, **owner)
        note(value.rpy, f"{parent}><origin", vector=True, **owner)

    for link in robot.links:
        inertial = link.inertial
        if inertial is not None:
            origin(inertial.origin, "inertial", link=link.name)
            note(inertial.mass, "mass", link=link.name)
            for value in inertial.tensor_values().values():
                note(value, "inertia", link=link.name)
        for shape in (*link.visuals, *link.collisions):
            origin(shape.origin, shape.kind, link=link.name)
            geometry = shape.geometry
            tag = type(geometry).__name__.lower()
            if isinstance(geometry, model.Box):
                note(geometry.size, "box", link=link.name, vector=True)
            elif isinstance(geometry, model.Cylinder | model.Capsule):
                note(geometry.radius, tag, link=link.name)
                note(geometry.length, tag, link=link.name)
            elif isinstance(geometry, model.Sphere):
                note(geometry.radius, "sphere", link=link.name)
            elif isinstance(geometry, model.Mesh):
                note(geometry.scale, "mesh", link=link.name, vector=True)
    for joint in robot.joints:
        origin(joint.origin, "joint", joint=joint.name)
        note(joint.axis, "axis", joint=joint.name, vector=True)
        limit, dynamics, mimic = joint.limit, joint.dynamics, joint.mimic
        if limit is not None:
            for value in (limit.lower, limit.upper, limit.effort, limit.velocity):
                note(value, "limit", joint=joint.name)
        if dynamics is not None:
            for value in (dynamics.damping, dynamics.friction):
                note(value, "dynamics", joint=joint.name)
        if mimic is not None:
            for value in (mimic.multiplier, mimic.offset):
                note(value, "mimic", joint=joint.name)
    return found


# values other values are divided by (physics/numbers.py: a tiny one is unusable too)
_SCALES = ("<mass value>", "<inertia ixx>", "<inertia iyy>", "<inertia izz>")


def _extreme(text: str, scale: bool = False) -> str | None:
    """
    Why a number URDF reads (finite, plain decimal) cannot be computed with (beyond ±1e50,
    subnormal, or for a ``scale`` below 1e-50: :mod:`inertia_kit.physics.numbers`), or
    ``None`` for any other text.
    """
    pieces = text.split()
    if not pieces or not all(_PLAIN.fullmatch(piece) for piece in pieces):
        return None
    reasons = [(piece, unusable(float(piece), scale)) for piece in pieces]
    if any(why in ("not a number", "infinite") for _, why in reasons):
        return None
    bad = dict.fromkeys((piece, why) for piece, why in reasons if why)
    if len(bad) == 1 and all(why for _, why in reasons):
        return next(iter(bad))[1]  # one number, or three alike
    return ", ".join(f"{piece} is {why}" for piece, why in bad) or None


def _describe(text: str, vector: bool, scale: bool = False) -> str:
    extreme = _extreme(text, scale)
    if extreme is not None and (not vector or len(text.split()) == 3):
        return extreme
    if vector:
        count = len(text.split())
        return f"{count} values, not 3" if count != 3 else "not three plain numbers"
    lowered = text.strip().lower()
    if lowered.lstrip("+-") == "nan":
        return "not a number"
    try:
        value = float(text)
    except ValueError:
        return "not a number"
    return "infinite" if math.isinf(value) else "not a number URDF accepts"


def _special(text: str) -> bool:
    """``nan``/``inf``: texts MuJoCo's number reader accepts."""
    return text.strip().lower().lstrip("+-") in ("nan", "inf", "infinity")


#: a value's text longer than this is cut short in the message (the detail has it whole)
LONG_TEXT = 32
#: the message names values while it stays this short; the rest are counted
MESSAGE_BUDGET = 100


def _shown(text: str) -> str:
    """The value's text as the message quotes it: cut short past :data:`LONG_TEXT`."""
    return repr(text if len(text) <= LONG_TEXT else text[: LONG_TEXT - 1] + "…")


def _listed(head: str, items: list[str]) -> str:
    """``head: item; item (+2 more)``: the items that keep the line short, the rest counted."""
    text = f"{head}: {items[0]}"
    for i, item in enumerate(items[1:], start=1):
        rest = len(items) - i - 1
        more = f" (+{rest} more)" if rest else ""
        if len(f"{text}; {item}{more}") > MESSAGE_BUDGET:
            return f"{text} (+{len(items) - i} more)"
        text += f"; {item}"
    return text


def _location(invalid: model.Invalid) -> tuple:
    source = invalid.source
    site = source.calls[-1] if source.calls else source
    return (site.path, site.line, site.column)


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    places = _places(robot.robot)
    # once per robot, not per finding: 5000 links with a bad number each was quadratic
    moving = {link.name for link in robot.links if link.moves}
    # one finding per location: attributes of one element (or of one xacro macro call) together
    groups: dict[tuple, list[model.Invalid]] = {}
    for invalid in robot.robot.invalid:
        groups.setdefault(_location(invalid), []).append(invalid)
    for invalids in groups.values():
        items = []  # the detail's, with every text whole
        short = []  # the message's
        pybullet = []
        owners = []
        for invalid in invalids:
            place = places.get(id(invalid), Place(f"<… {invalid.attribute}>"))
            if place.owner not in owners:
                owners.append(place.owner)
            scale = place.element in _SCALES
            described = _describe(invalid.text, place.vector, scale)
            items.append(f"`{place.element}` = {invalid.text!r} ({described})")
            short.append(f"`{place.element}` = {_shown(invalid.text)} ({described})")
            if _extreme(invalid.text, scale) is None:
                pybullet.append(f"{invalid.text!r} as {pybullet_reading(invalid, place.vector)}")
        first = places.get(id(invalids[0]), Place(""))
        # a fix from the geometry replaces the <inertial>: only a bad value in it is fixed
        fixable = first.element.startswith(("<inertial", "<mass", "<inertia "))
        # a moving link whose mass is not a number has none: it needs one (`--fix missing`)
        needs_mass = first.link is not None and first.link in moving
        repairs = Repairs.MISSING if needs_mass and first.element == "<mass value>" else None
        message = _listed(" and ".join(owners), short)
        if not pybullet:
            # every value reads as a number, one no robot has and no arithmetic keeps
            yield ctx.finding(
                message,
                invalids[0].source,
                detail=f"{'; '.join(items)}: no robot has such a value, and mass properties "
                "multiply and divide up to six numbers, which overflow or vanish in double "
                "precision beyond ±1e50 (and for a mass or moment, below 1e-50); the simulators "
                "read it and compute with it (MuJoCo, Drake), inertia-kit skips the checks that "
                "need it",
                link=first.link,
                joint=first.joint,
                fixable=fixable,
                repairs=repairs,
                help="write the value in SI units (kg, m, kg·m²), and a value meant to be zero "
                "as 0; in xacro, check the expression or property that produced it",
            )
            continue
        mujoco = (
            "MuJoCo reads nan/inf as they are"
            if all(_special(i.text) for i in invalids)
            else "MuJoCo refuses the file (bad format)"
        )
        yield ctx.finding(
            message,
            invalids[0].source,
            detail=f"{'; '.join(items)}: ROS (urdfdom) and Gazebo refuse the file, {mujoco}, "
            f"PyBullet silently reads {', '.join(pybullet)}",
            link=first.link,
            joint=first.joint,
            fixable=fixable,
            repairs=repairs,
            help="write a plain decimal number (`0.5`, `1e-3`: a dot for the decimal point, "
            "spaces between the three values of a vector, no units); in xacro, check the "
            "expression or property that produced it",
        )
