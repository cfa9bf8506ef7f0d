"""
Where a link's ``<inertial>`` is written, and the text edits that change it there.

In a URDF file every element is written once, where it stands. In xacro an element may come
from a macro body that several calls expand, so an edit there changes every link made from it.
A link's new values go to the first of these that works:

1. **The values that change, where each is written** (:mod:`.attributes`): a number in the
   ``<inertial>``, at the macro call that passes it, or in the macro's own property; values
   that do not change keep their text (``${wheel_mass}`` stays), and an expression is replaced
   by a number only when no place takes one (the link is then reported as no longer
   parametric). For a link without an ``<inertial>``, a block is inserted into its ``<link>``
   when every link made from that place gets the same values.
2. **The ``<inertial>`` replaced whole** where it is written, when every link made from it
   gets the same values (an ``<inertial>`` without ``<mass>`` or ``<inertia>`` to edit).
3. **The macro call that makes only the ``<inertial>``** (``<xacro:cylinder_inertia .../>``
   inside a link): the call is replaced by the literal block.

Values are compared as written (:mod:`.values`), and written as the next run reads them back
(:func:`~inertia_kit.description.writing.as_written`): a second run changes nothing.
Otherwise the link is not filled and the reason names the macro and what to do at each call.
Files outside the input's package (the folder holding the nearest ``package.xml``, else the
input's folder) are never edited.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

from inertia_kit.description import model
from inertia_kit.description.editing import Files, Key, insert_first_child, location
from inertia_kit.description.edits import Edit
from inertia_kit.description.placement import Placement, Target
from inertia_kit.description.urdf.placement.attributes import (
    ArgumentsChoose,
    Decision,
    Decisions,
    decide,
    write_values,
)
from inertia_kit.description.urdf.placement.xacro_macros import macro_of, written_name

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Source


def place(
    targets: Sequence[Target], links: Sequence[model.Link], files: Files
) -> dict[str, Placement]:
    """
    The edits that write each target's values (``links``: every link of the robot, to know
    which others share a macro body with a target).
    """
    wanted = {t.name: t for t in targets}
    decisions = Decisions({t.name: decide(t) for t in targets})
    users = _Users(links, files)
    placements: dict[str, Placement] = {}
    for target in targets:
        placements[target.name] = _place(target, wanted, decisions, users, files)
    return placements


class _Users:
    """
    Which links each written element makes (through their ``<inertial>`` or ``<link>``): one
    tuple per element, the same object each time it is asked for, so what is found of its
    links (:meth:`agree`, :func:`.attributes.users_agree`) is found once, not for each of
    them (a macro body 1667 links share, asked by each: quadratic).
    """

    def __init__(self, links: Sequence[model.Link], files: Files):
        body: dict[Key, list[str]] = {}
        made: dict[Key, list[str]] = {}
        chain: dict[Key, list[str]] = {}
        call: dict[tuple[Key, Key], list[str]] = {}
        for link in links:
            made.setdefault(files.key(link.source), []).append(link.name)
            inertial = link.inertial
            if inertial is None:
                continue
            body_key = files.key(inertial.source)
            body.setdefault(body_key, []).append(link.name)
            for site in inertial.source.calls:
                chain.setdefault(files.key(site), []).append(link.name)
            if inertial.source.calls:
                call.setdefault((files.key(inertial.source.calls[-1]), body_key), []).append(
                    link.name
                )
        self.body = {k: tuple(v) for k, v in body.items()}
        self.link = {k: tuple(v) for k, v in made.items()}
        self.chain = {k: tuple(v) for k, v in chain.items()}
        self.call = {k: tuple(v) for k, v in call.items()}
        self._agreed: dict[int, tuple[tuple[str, ...], bool]] = {}

    def agree(self, names: tuple[str, ...], wanted: Mapping[str, Target]) -> bool:
        """Whether every link in ``names`` is being filled, all with the same values; found
        once per group (``wanted`` is the same for every question)."""
        found = self._agreed.get(id(names))
        if found is None or found[0] is not names:  # the group kept: its id stays its own
            found = names, _agree(names, wanted)
            self._agreed[id(names)] = found
        return found[1]


def _agree(names: Sequence[str], wanted: Mapping[str, Target]) -> bool:
    """Whether every link in ``names`` is being filled, all with the same values."""
    if any(name not in wanted for name in names):
        return False
    return len({tuple(wanted[name].values.items()) for name in names}) == 1


def _place(
    target: Target,
    wanted: Mapping[str, Target],
    decisions: Mapping[str, Decision | None],
    users: _Users,
    files: Files,
) -> Placement:
    link = target.link
    inertial = link.inertial
    if inertial is None:
        sharers = users.link[files.key(link.source)]
        held = _conditional_inertials(files.element(link.source), files)
        if held and not users.agree(sharers, wanted):
            # what to do is the arguments, not a parameter: a block beside the condition
            # would give two <inertial> elements where it holds
            from inertia_kit.description.urdf.placement.conditionals import refusal

            return Placement(problem=refusal(held, files))
        if not users.agree(sharers, wanted):
            problem = _shared_words(link.source, sharers, "<link>")
            return Placement(problem=problem + _advice(link.source, sharers))
        return _insert(target, files)
    decision = decisions[target.name]
    if decision is not None and not decision.changed:
        return Placement()  # already says this, as written
    written = write_values(target, decisions, users, files)
    if not isinstance(written, str):
        return Placement(*written[:1], notes=written[1])
    if isinstance(written, ArgumentsChoose):
        return Placement(problem=written)
    for way in (_replace_body, _replace_call):
        result = way(target, wanted, users, files)
        if result.problem is None:
            return result
    # the first way's reason: the others (whole blocks) fail for the same sharing
    sharers = users.body[files.key(inertial.source)]
    advice = _advice(inertial.source, sharers, target, decisions, files)
    return Placement(problem=written + advice)


def _advice(
    where: Source,
    sharers: Sequence[str],
    target: Target | None = None,
    decisions: Mapping[str, Decision | None] | None = None,
    files: Files | None = None,
) -> str:
    """What to do: for an element one macro writes for several links, per call (pasting one
    link's values into the shared body would be wrong for the others): the macro, the values
    that differ between its links, this link's call and its own values; else paste the block
    (the caller shows it: ``inertia-fill`` below the reason, the linter in its ``unfixable``)."""
    if len(sharers) > 1 and where.calls:
        call = where.calls[-1]
        macro = _macro_name(where, files)
        differ = _differing(target, sharers, decisions)
        if differ:
            arguments = " ".join(f'{name}="{text}"' for name, text in differ.items())
            return (
                f"; a value written once cannot be right for links that differ: give {macro} "
                f"a parameter for each value that differs ({', '.join(differ)}) and pass each "
                f"link's own at its call: at this link's call, {location(call)}, {arguments}"
            )
        return (
            f"; a value written once cannot be right for links that differ: give {macro} a "
            "parameter for each value that differs and pass each link's own at its call "
            f"(this link's call: {location(call)})"
        )
    return "; paste its <inertial> there"


def _macro_name(where: Source, files: Files | None) -> str:
    from inertia_kit.description.urdf.placement.xacro_macros import enclosing_macro

    element = None if files is None else files.element(where)
    macro = None if element is None else enclosing_macro(element)
    return "the macro" if macro is None else f"macro `{macro.get('name', '?')}`"


def _differing(target, sharers, decisions) -> dict[str, str]:
    """``name -> this link's text`` for the values whose text differs between the links."""
    if target is None or decisions is None:
        return {}
    mine = decisions.get(target.name)
    others = [decisions.get(name) for name in sharers if name != target.name]
    if mine is None or any(d is None for d in others):
        return {}
    return {
        name: text
        for name, text in mine.texts.items()
        if any(d.texts[name] != text for d in others if d is not None)
    }


def _shared_words(where: Source, sharers: Sequence[str], what: str) -> str:
    names = ", ".join(f"`{n}`" for n in sharers[:6]) + (", ..." if len(sharers) > 6 else "")
    return (
        f"its {what} is written once ({location(where)}) for {len(sharers)} links ({names}) "
        "that need different values"
    )


def _insert(target: Target, files: Files) -> Placement:
    from inertia_kit.description.xmlspan import line_indent

    where = target.link.source
    found = files.span(where, "link")
    if isinstance(found, str):
        return Placement(problem=f"its {found}")
    source, span = found
    block = _block(target, source, line_indent(source.text, span.start), inner=True)
    block, problem = _guarded(block, files.element(where), files, source)
    if problem is not None:
        return Placement(problem=problem)
    if span.empty:  # <link name="x"/>: no geometry, never filled; defensive
        return Placement(problem=f"its <link> at {location(where)} is an empty element")
    return Placement((insert_first_child(source, span, block),))


def _conditional_inertials(link: etree._Element | None, files: Files) -> list[etree._Element]:
    from inertia_kit.description.urdf.placement.conditionals import conditional_inertials

    return [] if link is None else conditional_inertials(link, files)


def _guarded(
    block: str, link: etree._Element | None, files: Files, source: SourceText
) -> tuple[str, str | None]:
    """
    ``block`` as it may be inserted into ``link``: inside the complement of the conditions
    under which the link makes an ``<inertial>`` of its own (so that no argument value expands
    two); or why not.
    """
    from inertia_kit.description.urdf.placement import conditionals

    if link is None:
        return block, "its <link> was not found where the load read it"
    held = _conditional_inertials(link, files)
    if not held:
        return block, None
    tags = conditionals.complementary(held)
    if tags is None:
        return block, conditionals.refusal(held, files)
    from inertia_kit.description.xmlspan import indent_unit

    indent = re.match(r"[ \t]*", block).group(0)  # type: ignore[union-attr]
    unit, newline = indent_unit(source.text), source.newline
    inner = newline.join(unit + line for line in block.split(newline))
    return f"{indent}{tags[0]}{newline}{inner}{newline}{indent}{tags[1]}", None


def _block(target: Target, source: SourceText, base: str, *, inner: bool) -> str:
    """The ``<inertial>`` text at indentation ``base`` (plus one level when ``inner``); its
    first line unindented when it replaces an element in place (``inner`` false)."""
    from inertia_kit.description.urdf.inertial_xml import inertial_block
    from inertia_kit.description.xmlspan import indent_unit

    unit = indent_unit(source.text)
    lines = inertial_block(target.properties, indent=unit, level=0, newline="\n").split("\n")
    if inner:
        return source.newline.join(base + unit + line for line in lines)
    return source.newline.join([lines[0], *(base + line for line in lines[1:])])


def _replace_element(target: Target, where: Source, tag: str, files: Files) -> Placement:
    from inertia_kit.description.xmlspan import line_indent

    found = files.span(where, tag)
    if isinstance(found, str):
        return Placement(problem=found)
    source, span = found
    block = _block(target, source, line_indent(source.text, span.start), inner=False)
    return Placement((Edit(source.path, span.start, span.end, block),))


def _replace_body(target: Target, wanted, users: _Users, files: Files) -> Placement:
    """Way 1: the ``<inertial>`` where it is written."""
    inertial = target.link.inertial
    assert inertial is not None
    sharers = users.body[files.key(inertial.source)]
    if not users.agree(sharers, wanted):
        return Placement(problem=_shared_words(inertial.source, sharers, "<inertial>"))
    placed = _replace_element(target, inertial.source, "inertial", files)
    body = files.element(inertial.source)
    lost = (
        []
        if body is None
        else [
            value for element in body.iter() for value in element.attrib.values() if "${" in value
        ]
    )
    if placed.problem is None and lost:
        note = (
            f"link `{target.name}` is no longer parametric: its <inertial> at "
            f"{location(inertial.source)} is written as numbers where it read "
            + ", ".join(f'"{v}"' for v in lost[:4])
        )
        return Placement(placed.edits, notes=(note,))
    return placed


def _replace_call(target: Target, wanted, users: _Users, files: Files) -> Placement:
    """Way 3: a macro call whose expansion is just this ``<inertial>``, innermost first."""
    inertial = target.link.inertial
    assert inertial is not None
    chain = (*inertial.source.calls, inertial.source)
    for index in range(len(chain) - 2, -1, -1):
        call, made = chain[index], chain[index + 1]
        element = files.element(made)
        macro = None if element is None else macro_of(element)
        if macro is None or [c for c in macro if isinstance(c.tag, str)] != [element]:
            continue  # the macro makes more than this element
        if not users.agree(users.chain.get(files.key(call), ()), wanted):
            continue
        call_element = files.element(call)
        if call_element is None:
            continue
        tag = written_name(call_element)
        placed = _replace_element(target, call, tag, files)
        arguments = [v for v in call_element.attrib.values() if "${" in v or "$(" in v]
        if placed.problem is None and arguments:
            lost = ", ".join(f'"{v}"' for v in arguments)
            note = (
                f"link `{target.name}` is no longer parametric: the call at {location(call)} "
                f"passing {lost} is replaced by its <inertial> written as numbers"
            )
            return Placement(placed.edits, notes=(note,))
        return placed
    if not inertial.source.calls:
        return Placement(problem="the <inertial> is not made by a macro call")
    return Placement(problem="no macro call makes only this <inertial>")
