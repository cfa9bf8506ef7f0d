"""
Values under ``<xacro:if>``/``<xacro:unless>``: a fill must hold for every argument value, not
only the ones it was run with.

Two slips it must not make (franka_ros' fingers, husarion's rosbot wheels):

- **A block that shadows another.** A link whose ``<inertial>`` sits in a conditional
  (``<xacro:if value="${gazebo}"><xacro:inertial_props .../></xacro:if>``) has none with the
  default arguments; an unconditional block inserted for it gives the link two ``<inertial>``
  elements when the condition holds, and the inserted one, first, is the one every reader takes.
  The new block goes into the complementary condition instead
  (``<xacro:unless value="${gazebo}">``), so that each argument value expands exactly one.
- **An edit in a branch the arguments do not expand.** A macro defining ``mass`` once under
  ``<xacro:if value="${mecanum}">`` and once under ``<xacro:unless ...>`` reads the second with
  the default arguments; the value is written to the definition the expansion read, found by
  loading the robot once with each candidate given a distinct stand-in value
  (:meth:`~inertia_kit.description.editing.Files.expanded`). An expression reading such a
  value is never replaced by a number: that number would then hold for every argument value.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import TYPE_CHECKING

from inertia_kit.description.editing import Files, location
from inertia_kit.description.urdf.placement.xacro_macros import enclosing_macro, is_xacro

if TYPE_CHECKING:
    from lxml import etree

_CONDITIONS = ("if", "unless")
# what a macro call may be written as: ``xacro:name``, ``xacro:ns.name``
_NAME = re.compile(r"[^.]+$")


def conditions(element: etree._Element, stop: etree._Element | None = None) -> list[etree._Element]:
    """The ``<xacro:if>``/``<xacro:unless>`` elements holding ``element``, innermost first, up
    to ``stop`` (not included)."""
    found = []
    parent = element.getparent()
    while parent is not None and parent is not stop:
        if any(is_xacro(parent, name) for name in _CONDITIONS):
            found.append(parent)
        parent = parent.getparent()
    return found


def written(condition: etree._Element) -> str:
    """``<xacro:if value="${gazebo}">``, as a message quotes it."""
    kind = "if" if is_xacro(condition, "if") else "unless"
    return f'<xacro:{kind} value="{condition.get("value", "")}">'


def conditional_inertials(link: etree._Element, files: Files) -> list[etree._Element]:
    """
    The conditions inside ``link`` (a ``<link>`` as written) that hold an ``<inertial>``, or a
    call of a macro that makes one, outermost first: with some argument values the link gets
    that ``<inertial>``. A call of a macro that is not found counts (it may make one).
    """
    found = []
    for element in link.iter():
        if element is link or not isinstance(element.tag, str):
            continue
        if not _makes_inertial(element, files, set()):
            continue
        held = conditions(element, link)
        if held and held[-1] not in found:
            found.append(held[-1])
    return found


def _makes_inertial(element: etree._Element, files: Files, seen: set[str]) -> bool:
    from lxml import etree

    if element.tag == "inertial":
        return True
    qname = etree.QName(element)
    if "xacro" not in (qname.namespace or "") or qname.localname in _KEYWORDS:
        return False
    name = _NAME.search(qname.localname).group(0)  # type: ignore[union-attr]
    if name in seen:
        return False
    seen.add(name)
    bodies = files.macros().get(name)
    if not bodies:
        return True  # not found: it may make one
    return any(
        _makes_inertial(inner, files, seen)
        for body in bodies
        for inner in body.iter()
        if inner is not body and isinstance(inner.tag, str)
    )


# xacro's own elements, which are no macro calls (``xacro:call`` is one, of a macro named at
# expansion: not found, so it counts)
_KEYWORDS = frozenset(
    {
        "if",
        "unless",
        "property",
        "arg",
        "include",
        "macro",
        "insert_block",
        "element",
        "attribute",
        "load_yaml",
    }
)


def complementary(held: Sequence[etree._Element]) -> tuple[str, str] | None:
    """
    The start and end tags that expand their content exactly when none of the conditions
    ``held`` does (each ``if`` turned into ``unless`` and back, nested); ``None`` when one of
    them sits inside another (its complement is no single condition's).
    """
    if any(set(conditions(c)) & set(held) for c in held):
        return None
    start, end = "", ""
    for condition in held:
        kind = "unless" if is_xacro(condition, "if") else "if"
        value = condition.get("value")
        if value is None:
            return None
        start += f'<xacro:{kind} value="{_attribute(value)}">'
        end = f"</xacro:{kind}>" + end
    return start, end


def _attribute(value: str) -> str:
    return value.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


def refusal(held: Sequence[etree._Element], files: Files) -> str:
    """Why no block is inserted: the conditions, where they stand, and what to do."""
    places = ", ".join(f"{written(c)} ({_where(c, files)})" for c in held)
    return (
        f"its <inertial> is made only under {places}: fill with arguments that expand it "
        "(--xacro-arg NAME:=VALUE), or write the values in a branch of the other value (a "
        "block beside it would be a second <inertial> where it holds)"
    )


def _where(element: etree._Element, files: Files) -> str:
    where = files.where(element)
    return "?" if where is None else location(where)


def definitions(element: etree._Element, name: str) -> list[etree._Element]:
    """Every ``<xacro:property name=NAME value=...>`` of the innermost macro holding ``element``
    (in that macro itself, not in a macro it defines), in document order."""
    macro = enclosing_macro(element)
    if macro is None:
        return []
    return [
        candidate
        for candidate in macro.iter()
        if is_xacro(candidate, "property")
        and candidate.get("name") == name
        and candidate.get("value") is not None
        and enclosing_macro(candidate) is macro
    ]


def conditional(found: Sequence[etree._Element]) -> bool:
    """Whether which of the definitions ``found`` is read depends on the arguments."""
    return len(found) > 1 or any(conditions(d, enclosing_macro(d)) for d in found)


def chosen_by_arguments(element: etree._Element, names: Sequence[str]) -> list[etree._Element]:
    """The definitions of ``names`` in ``element``'s file, outside any macro, whose value the
    arguments choose: under a condition, or reading an argument (``$(arg payload)``)."""
    root = element.getroottree().getroot()
    return [
        candidate
        for candidate in root.iter()
        if is_xacro(candidate, "property")
        and candidate.get("name") in names
        and enclosing_macro(candidate) is None
        and (conditions(candidate) or "$(arg" in (candidate.get("value") or ""))
    ]
