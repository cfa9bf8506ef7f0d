"""
Where a link's ``<inertial>`` is written, and the text edits that change it there.

In a URDF file every element is written once, where it stands. In xacro an element may come
from a macro body that several calls expand, so an edit there changes every link made from it.
A link's new values go to the first of these that works:

1. **The element itself**: the ``<inertial>`` is replaced (or, for a link without one, a block
   is inserted into the ``<link>``) where it is written, when every link made from that place
   gets the same values: a literal link, a macro used once, identical copies such as two wheels.
2. **The macro call's parameters**: the macro writes ``<inertia ixx="${ixx}" ...>`` and the
   call passes ``ixx="13.235"``; the number at that call is replaced (added, for a parameter
   the call leaves to its default). Every value that must change has to be a parameter used
   nowhere else in the macro (``origin_xyz`` that also places the collision is only accepted
   while the centre of mass stays where it is). Tried first for a macro used several times.
3. **The macro call that makes only the ``<inertial>``** (``<xacro:cylinder_inertia .../>``
   inside a link): the call is replaced by the literal block.

Otherwise the link is not filled and the reason names the macro and what stopped each way;
:func:`inertial_block` gives the block to paste. Files outside the input's package (the folder
holding the nearest ``package.xml``, else the input's folder) are never edited.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from inertia_kit.description.edits import Edit
from inertia_kit.description.model import Inertial
from inertia_kit.fixes.files import Files, Key, key, location
from inertia_kit.fixes.xacro_macros import (
    child,
    enclosing_macro,
    macro_of,
    parameter_names,
    parameter_reference,
    used_elsewhere,
    written_name,
)
from inertia_kit.physics.formatting import xml_number

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.analysis.links import LinkAnalysis
    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Source
    from inertia_kit.physics.mass import MassProperties


def written_values(properties: MassProperties, rpy=(0.0, 0.0, 0.0)) -> dict[str, str]:
    """The text of each value an ``<inertial>`` with ``<origin rpy>`` = ``rpy`` writes."""
    from inertia_kit.description.inertial_xml import inertial_values

    values = inertial_values(properties, rpy=rpy)
    del values["rpy"]
    return values


@dataclass(frozen=True)
class Target:
    """A link to fill with ``properties`` (link frame, about its centre of mass); ``basis``
    says where its mass comes from."""

    link: LinkAnalysis
    properties: MassProperties
    basis: str = ""

    @property
    def name(self) -> str:
        return self.link.name

    @functools.cached_property
    def values(self) -> dict[str, str]:
        """The text written for each value (compared across links sharing a macro body)."""
        return written_values(self.properties)


@dataclass(frozen=True)
class Placement:
    """How a link's values get into its files: ``edits`` (empty: already there), or ``problem``."""

    edits: tuple[Edit, ...] = ()
    problem: str | None = None


def place(
    targets: Sequence[Target], links: Sequence[LinkAnalysis], files: Files
) -> dict[str, Placement]:
    """
    The edits that write each target's values (``links``: every link of the robot, to know
    which others share a macro body with a target).
    """
    wanted = {t.name: t for t in targets}
    users = _Users(links)
    placements: dict[str, Placement] = {}
    for target in targets:
        placements[target.name] = _place(target, wanted, users, files)
    return placements


class _Users:
    """Which links each written element makes (through their ``<inertial>`` or ``<link>``)."""

    def __init__(self, links: Sequence[LinkAnalysis]):
        self.body: dict[Key, list[str]] = {}
        self.link: dict[Key, list[str]] = {}
        self.chain: dict[Key, list[str]] = {}
        self.call: dict[tuple[Key, Key], list[str]] = {}
        for link in links:
            self.link.setdefault(key(link.link.source), []).append(link.name)
            inertial = link.link.inertial
            if inertial is None:
                continue
            body = key(inertial.source)
            self.body.setdefault(body, []).append(link.name)
            for call in inertial.source.calls:
                self.chain.setdefault(key(call), []).append(link.name)
            if inertial.source.calls:
                self.call.setdefault((key(inertial.source.calls[-1]), body), []).append(link.name)


def _agree(names: Sequence[str], wanted: Mapping[str, Target]) -> bool:
    """Whether every link in ``names`` is being filled, all with the same values."""
    if any(name not in wanted for name in names):
        return False
    return len({tuple(wanted[name].values.items()) for name in names}) == 1


def _place(target: Target, wanted: Mapping[str, Target], users: _Users, files: Files) -> Placement:
    link = target.link
    inertial = link.link.inertial
    if inertial is None:
        sharers = users.link[key(link.link.source)]
        if not _agree(sharers, wanted):
            return Placement(problem=_shared_words(link.link.source, sharers, "<link>"))
        return _insert(target, files)
    declared = link.declared
    if declared is not None and written_values(declared) == target.values:
        return Placement()  # already says this
    sharers = users.body[key(inertial.source)]
    ways = [_replace_body, _parameters, _replace_call]
    if len(sharers) > 1:
        ways = [_parameters, _replace_body, _replace_call]
    problems = []
    for way in ways:
        result = way(target, wanted, users, files)
        if result.problem is None:
            return result
        problems.append(result.problem)
    return Placement(problem="; ".join(dict.fromkeys(problems)))


def _shared_words(where: Source, sharers: Sequence[str], what: str) -> str:
    names = ", ".join(f"`{n}`" for n in sharers[:6]) + (", ..." if len(sharers) > 6 else "")
    return (
        f"its {what} is written once ({location(where)}) for {len(sharers)} links ({names}) "
        "that need different values"
    )


def _insert(target: Target, files: Files) -> Placement:
    from inertia_kit.description.xmlspan import element_span, line_indent

    where = target.link.link.source
    if not files.editable(where.path):
        return Placement(
            problem=f"its <link> is written in {location(where)}, {files.outside(where.path)}"
        )
    offset = files.offset(where, "link")
    if offset is None:
        return Placement(problem=f"its <link> was not found at {location(where)}")
    source = files.source(where.path)
    text = source.text
    span = element_span(text, offset)
    block = _block(target, source, line_indent(text, offset), inner=True)
    newline = source.newline
    if span.empty:  # <link name="x"/>: no geometry, never filled; defensive
        return Placement(problem=f"its <link> at {location(where)} is an empty element")
    rest = re.compile(r"[ \t]*(\r\n|\n|\r)").match(text, span.start_tag_end)
    if rest is not None:
        edit = Edit(source.path, rest.end(), rest.end(), block + newline)
    else:  # the link's content follows its start tag on the same line
        edit = Edit(
            source.path,
            span.start_tag_end,
            span.start_tag_end,
            newline + block + newline + line_indent(text, span.start),
        )
    return Placement((edit,))


def _block(target: Target, source: SourceText, base: str, *, inner: bool) -> str:
    """The ``<inertial>`` text at indentation ``base`` (plus one level when ``inner``); its
    first line unindented when it replaces an element in place (``inner`` false)."""
    from inertia_kit.description.inertial_xml import inertial_block
    from inertia_kit.description.xmlspan import indent_unit

    unit = indent_unit(source.text)
    lines = inertial_block(target.properties, indent=unit, level=0, newline="\n").split("\n")
    if inner:
        return source.newline.join(base + unit + line for line in lines)
    return source.newline.join([lines[0], *(base + line for line in lines[1:])])


def _replace_element(target: Target, where: Source, tag: str, files: Files) -> Placement:
    from inertia_kit.description.xmlspan import element_span, line_indent

    if not files.editable(where.path):
        return Placement(
            problem=f"<{tag}> is written in {location(where)}, {files.outside(where.path)}"
        )
    offset = files.offset(where, tag)
    if offset is None:
        return Placement(problem=f"<{tag}> was not found at {location(where)}")
    source = files.source(where.path)
    span = element_span(source.text, offset)
    block = _block(target, source, line_indent(source.text, offset), inner=False)
    return Placement((Edit(source.path, span.start, span.end, block),))


def _replace_body(target: Target, wanted, users: _Users, files: Files) -> Placement:
    """Way 1: the ``<inertial>`` where it is written."""
    inertial = target.link.link.inertial
    assert inertial is not None
    sharers = users.body[key(inertial.source)]
    if not _agree(sharers, wanted):
        return Placement(problem=_shared_words(inertial.source, sharers, "<inertial>"))
    return _replace_element(target, inertial.source, "inertial", files)


def _replace_call(target: Target, wanted, users: _Users, files: Files) -> Placement:
    """Way 3: a macro call whose expansion is just this ``<inertial>``, innermost first."""
    inertial = target.link.link.inertial
    assert inertial is not None
    chain = (*inertial.source.calls, inertial.source)
    for index in range(len(chain) - 2, -1, -1):
        call, made = chain[index], chain[index + 1]
        element = files.element(made)
        macro = None if element is None else macro_of(element)
        if macro is None or [c for c in macro if isinstance(c.tag, str)] != [element]:
            continue  # the macro makes more than this element
        if not _agree(users.chain.get(key(call), []), wanted):
            continue
        call_element = files.element(call)
        if call_element is None:
            continue
        tag = written_name(call_element)
        return _replace_element(target, call, tag, files)
    if not inertial.source.calls:
        return Placement(problem="the <inertial> is not made by a macro call")
    return Placement(problem="no macro call makes only this <inertial>")


def _parameters(target: Target, wanted, users: _Users, files: Files) -> Placement:
    """Way 2: the numbers the innermost macro call passes for the values that change."""
    from inertia_kit.description.inertial_xml import DIGITS

    link = target.link
    inertial = link.link.inertial
    assert inertial is not None
    if not inertial.source.calls:
        return Placement(problem="the <inertial> is not made by a macro call")
    call = inertial.source.calls[-1]
    body = files.element(inertial.source)
    macro = None if body is None else enclosing_macro(body)
    call_element = files.element(call)
    if body is None or macro is None or call_element is None:
        return Placement(problem="its macro was not found")
    macro_name = macro.get("name", "?")
    if not files.editable(call.path):
        return Placement(problem=f"the call at {location(call)} is {files.outside(call.path)}")
    rpy = inertial.origin.rpy if isinstance(inertial.origin.rpy, tuple) else (0.0, 0.0, 0.0)
    new = written_values(target.properties, rpy)
    declared = link.declared
    if declared is None or not isinstance(inertial.origin.rpy, tuple):
        return Placement(problem="its declared <inertial> is not complete and numeric")
    old = written_values(declared, rpy)
    # the current written tensor, not the link-frame one recomputed: what the file says
    old.update(
        {
            name: xml_number(getattr(inertial, name), DIGITS)
            for name in Inertial.TENSOR
            if isinstance(getattr(inertial, name), float)
        }
    )
    old["mass"] = xml_number(inertial.mass, DIGITS)
    attributes = {
        "mass": (child(body, "mass"), "value"),
        "xyz": (child(body, "origin"), "xyz"),
        **{name: (child(body, "inertia"), name) for name in Inertial.TENSOR},
    }
    parameters = parameter_names(macro)
    changes: dict[str, str] = {}  # parameter -> new text
    mapped: dict[str, list[tuple[etree._Element, str]]] = {}
    for name, (element, attribute) in attributes.items():
        text = None if element is None else element.get(attribute)
        if name == "xyz" and text is None:
            text = "0 0 0"
        parameter = None if text is None else parameter_reference(text)
        if parameter is not None and parameter in parameters:
            mapped.setdefault(parameter, []).append((element, attribute))
            if changes.get(parameter, new[name]) != new[name]:
                return Placement(problem=f"parameter `{parameter}` would need two values")
            if old[name] != new[name]:
                changes[parameter] = new[name]
            continue
        if old[name] != new[name]:
            label = "the centre of mass" if name == "xyz" else f"`{name}`"
            written = "absent" if text is None else f"`{text}`"
            return Placement(
                problem=f"{label} in macro `{macro_name}` ({location(inertial.source)}) is "
                f"{written}, "
                "not a parameter the call passes"
            )
    sharers = users.call[(key(call), key(inertial.source))]
    if changes and not _agree(sharers, wanted):
        return Placement(problem=_shared_words(call, sharers, f"call of `{macro_name}`"))
    edits = []
    for parameter, value in changes.items():
        if used_elsewhere(macro, parameter, mapped[parameter]):
            return Placement(
                problem=f"parameter `{parameter}` of `{macro_name}` is used for more than the "
                f"<inertial>: changing it to {value} would change the rest"
            )
        edit = _attribute_edit(files, call, call_element, parameter, value, parameters[parameter])
        if isinstance(edit, str):
            return Placement(problem=edit)
        edits.append(edit)
    return Placement(tuple(edits))


def _attribute_edit(files, call: Source, element, parameter: str, value: str, has_default: bool):
    """The edit setting ``parameter="value"`` on the call's start tag, or why it cannot."""
    from inertia_kit.description.xmlspan import element_span

    source = files.source(call.path)
    offset = files.offset(call, written_name(element))
    if offset is None:
        return f"the call at {location(call)} was not found"
    span = element_span(source.text, offset)
    start_tag = source.text[offset : span.start_tag_end]
    match = re.search(rf"(\s){re.escape(parameter)}\s*=\s*(\"([^\"]*)\"|'([^']*)')", start_tag)
    if match is None:
        if not has_default:
            return f"the call at {location(call)} does not pass `{parameter}`"
        end = span.start_tag_end - (2 if span.empty else 1)
        while end > offset and source.text[end - 1] in " \t\r\n":
            end -= 1
        return Edit(source.path, end, end, f' {parameter}="{value}"')
    written = match.group(3) if match.group(3) is not None else match.group(4)
    if "${" in written or "$(" in written:
        return (
            f'the call at {location(call)} passes {parameter}="{written}", an expression: '
            f"write {value} there or in what it names"
        )
    group = 3 if match.group(3) is not None else 4
    return Edit(source.path, offset + match.start(group), offset + match.end(group), value)
