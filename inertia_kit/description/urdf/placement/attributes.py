"""
Way 1 of :mod:`.sites`: the values that change, each where its text is written, and nothing
else.

A value's text may be written in the ``<inertial>`` itself (``ixx="0.01"``), passed through a
macro's parameter (``ixx="${ixx}"`` in the body, ``ixx="0.01"`` at the call, perhaps through
several calls), or read from a property defined in the macro (``ixx="${inertia_ixx}"``). The
*slots* of a value are these places, innermost first; each is written once for the links it
makes (its users). A new value is written at the outermost slot whose users all get that same
text, where the text is a number (or absent with a default), so expressions elsewhere stay. Only
when no such slot exists is an expression replaced by the number, and the link is reported as
no longer parametric.

The axes of the ``<inertial>``: a link made of one shape whose ``<origin rpy>`` turns it (the
seed arm's cylinder along x) may keep a tensor written in the shape's own axes, as its author
meant; then the ``<inertial>`` takes the shape's ``<origin>``, copied as the shape writes it
(``xyz="${link_length/2} 0 0" rpy="0 ${pi/2} 0"``) where it is read in the same scope. When
the ``<inertial>`` comes from a macro without an ``<origin>`` and its links need different
ones, the macro gains optional parameters ``origin_xyz:='0 0 0' origin_rpy:='0 0 0'``, and
only the calls that need another origin pass one.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

from inertia_kit.description.editing import Files, location
from inertia_kit.description.urdf.placement.values import (
    ZERO,
    differing,
    new_texts,
    same_vector,
    vector,
)
from inertia_kit.description.urdf.placement.writer import Writer
from inertia_kit.description.urdf.placement.xacro_macros import (
    child,
    enclosing_macro,
    parameter_names,
    parameter_reference,
    used_elsewhere,
    uses,
)

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.edits import Edit
    from inertia_kit.description.model import Source
    from inertia_kit.description.placement import Target

_EXPRESSION = re.compile(r"\$\{([^}]*)\}")
_ELEMENT = {"xyz": ("origin", "xyz"), "rpy": ("origin", "rpy"), "mass": ("mass", "value")}
DEFAULT_ORIGIN = "0 0 0"


class ArgumentsChoose(str):
    """Why a value cannot be written: the arguments choose what the link reads there, so no
    number may replace the expression, in that place or by replacing the whole block."""


@dataclass(frozen=True)
class Decision:
    """What a target's ``<inertial>`` will say: in the axes ``rpy``, each value's ``texts``;
    the names that change; for ``xyz``/``rpy``, the shape ``<origin>`` saying the same."""

    rpy: tuple[float, float, float]
    texts: dict[str, str]
    changed: tuple[str, ...]
    copied: dict[str, Source] = field(default_factory=dict)


def decide(target: Target) -> Decision | None:
    """The axes that change the fewest values: the ``<inertial>``'s own, else (a link of one
    turned shape) the shape's; ``None`` for a link without an ``<inertial>``."""
    from inertia_kit.description.urdf.inertial_xml import exact_values

    inertial = target.link.inertial
    if inertial is None:
        return None
    current = vector(inertial.origin.rpy) or ZERO
    candidates: list[tuple[tuple[float, float, float], Source | None]] = [(current, None)]
    shapes = target.shapes
    if len(shapes) == 1:
        origin = shapes[0].origin
        turned = vector(origin.rpy)
        if turned is not None and any(turned) and turned != current:
            candidates.append((turned, origin.source))
    best: Decision | None = None
    for rpy, shape in candidates:
        texts = new_texts(target.properties, rpy)
        changed = tuple(differing(inertial, texts, exact_values(target.properties, rpy)))
        copied = {}
        if shape is not None:
            copied["rpy"] = shape
            if same_vector(texts["xyz"], shapes[0].origin.xyz):
                copied["xyz"] = shape
        if best is None or len(changed) < len(best.changed):
            best = Decision(rpy, texts, changed, copied)
    return best


@dataclass(frozen=True)
class Slot:
    """Where a value's text is written: ``attribute`` of ``element`` (``holder`` when the
    element is absent), for the links ``users``."""

    element: etree._Element | None
    attribute: str
    users: tuple[str, ...]
    call: bool = False  # a macro call's argument
    has_default: bool = False  # ... that the macro gives a default
    stop: str | None = None  # why the value is not followed further out

    @property
    def text(self) -> str | None:
        return None if self.element is None else self.element.get(self.attribute)


class Decisions(dict):
    """Each target's :class:`Decision`, fixed while its fixes are placed, with what
    :func:`users_agree` found of each group of links (asked by each link of a group)."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **kwargs)
        self.agreed: dict[tuple[int, str], tuple[tuple[str, ...], bool]] = {}


def users_agree(
    users: tuple[str, ...], name: str, decisions: Mapping[str, Decision | None]
) -> bool:
    """Whether every link of ``users`` writes the same text for value ``name``; found once per
    group when ``decisions`` is a :class:`Decisions`."""
    if not isinstance(decisions, Decisions):
        return _users_agree(users, name, decisions)
    found = decisions.agreed.get((id(users), name))
    if found is None or found[0] is not users:  # the group kept with the answer: ids stay its
        found = users, _users_agree(users, name, decisions)
        decisions.agreed[(id(users), name)] = found
    return found[1]


def _users_agree(
    users: tuple[str, ...], name: str, decisions: Mapping[str, Decision | None]
) -> bool:
    texts = set()
    for user in users:
        decision = decisions.get(user)
        if decision is None:
            return False
        texts.add(decision.texts[name])
    return len(texts) == 1


def chain(name: str, body: etree._Element, target: Target, users, files: Files) -> list[Slot]:
    """The slots of value ``name``, innermost (the ``<inertial>`` body) first."""
    inertial = target.link.inertial
    assert inertial is not None
    tag, attribute = _ELEMENT.get(name, ("inertia", name))
    element = child(body, tag)
    slots = [Slot(element, attribute, tuple(users.body[files.key(inertial.source)]))]
    calls = inertial.source.calls
    index, macro, here = len(calls) - 1, enclosing_macro(body), slots[0]
    while here.text is not None and index >= 0 and macro is not None:
        parameter = parameter_reference(here.text)
        names = parameter_names(macro)
        if parameter is None or parameter not in names:
            break
        level = body if not here.call else here.element
        mapped = _mapped(level, parameter, nested=not here.call)
        if used_elsewhere(macro, parameter, mapped):
            # changing the argument would change more than this value
            here = Slot(
                here.element,
                here.attribute,
                here.users,
                here.call,
                here.has_default,
                f"parameter `{parameter}` of `{macro.get('name', '?')}` is used for more than "
                "the <inertial>",
            )
            slots[-1] = here
            break
        call = files.element(calls[index])
        if call is None:
            break
        made = tuple(users.chain.get(files.key(calls[index]), ()))
        here = Slot(call, parameter, made, call=True, has_default=names[parameter])
        slots.append(here)
        index, macro = index - 1, enclosing_macro(call)
    return slots


def _mapped(level: etree._Element, parameter: str, *, nested: bool):
    """The attributes at this level that are exactly ``${parameter}``: a body's values (in its
    children) or a call's arguments."""
    elements = list(level) if nested else [level]
    return [
        (element, name)
        for element in elements
        if isinstance(element.tag, str)
        for name, value in element.attrib.items()
        if parameter_reference(value) == parameter
    ]


def _expression(text: str) -> bool:
    return "${" in text or "$(" in text


def _same_scope(a: etree._Element, b: etree._Element, files: Files) -> bool:
    """Whether an expression read at ``b`` means the same at ``a``: one file, one macro."""
    where_a, where_b = files.where(a), files.where(b)
    if where_a is None or where_b is None:
        return False
    same_file = files.real(where_a.path) == files.real(where_b.path)
    return same_file and enclosing_macro(a) is enclosing_macro(b)


def text_at(
    slot_element: etree._Element,
    name: str,
    decision: Decision,
    users: tuple[str, ...],
    decisions: Mapping[str, Decision | None],
    files: Files,
) -> tuple[str, str | None]:
    """The text to write for ``name`` at a slot: the shape's ``<origin>`` text when every user
    copies the same one and it reads the same here, else the number; and the expression lost
    (``None``: none)."""
    number = decision.texts[name]
    shape = decision.copied.get(name)
    if shape is None:
        return number, None
    copies = [decisions.get(user) for user in users]
    same = {files.key(d.copied[name]) if d and name in d.copied else None for d in copies}
    shape_element = files.element(shape)
    text = None if shape_element is None else shape_element.get(name)
    if text is None or len(same) != 1:
        return number, None
    if _same_scope(slot_element, shape_element, files):
        return text, None
    return number, text if _expression(text) else None


def write_values(
    target: Target, decisions: Mapping[str, Decision | None], users, files: Files
) -> tuple[tuple[Edit, ...], tuple[str, ...]] | str:
    """The edits writing ``target``'s changed values where they are written, and the notes on
    expressions replaced by numbers; or why they cannot be written so."""
    decision = decisions[target.name]
    inertial = target.link.inertial
    assert decision is not None and inertial is not None
    body = files.element(inertial.source)
    if body is None:
        return f"its <inertial> was not found at {location(inertial.source)}"
    if child(body, "mass") is None or child(body, "inertia") is None:
        return "its <inertial> has no <mass> or <inertia> to edit"
    writer = Writer(files)
    absent = []
    for name in decision.changed:
        slots = chain(name, body, target, users, files)
        if slots[0].text is None and name in ("xyz", "rpy"):
            absent.append(name)
            continue
        problem = _write_value(name, slots, target, decisions, writer)
        if problem is not None:
            return problem
    if absent:
        from inertia_kit.description.urdf.placement.origins import write_origin

        problem = write_origin(absent, body, target, decisions, users, writer)
        if problem is not None:
            return problem
    return writer.result(), tuple(writer.notes)


def _write_value(
    name: str,
    slots: list[Slot],
    target: Target,
    decisions: Mapping[str, Decision | None],
    writer: Writer,
) -> str | None:
    """Write one value at its outermost slot that takes a number, else replace an expression."""
    decision = decisions[target.name]
    assert decision is not None
    files = writer.files
    agreeing = [slot for slot in reversed(slots) if users_agree(slot.users, name, decisions)]
    for slot in agreeing:  # first: a number or an absent argument, keeping every expression
        text = slot.text
        if slot.element is None:
            continue
        if text is None:
            if slot.call and slot.has_default:
                new, _ = text_at(slot.element, name, decision, slot.users, decisions, files)
                return writer.set(slot.element, slot.attribute, new)
            continue
        if not _expression(text):
            new, lost = text_at(slot.element, name, decision, slot.users, decisions, files)
            note_lost(writer, target, name, new, lost, slot, shape=True)
            return writer.set(slot.element, slot.attribute, new)
        definition = _definition(slot, name, target, files)
        if isinstance(definition, str):
            return definition
        if definition is not None and not _expression(definition.get("value", "")):
            return writer.set(definition, "value", decision.texts[name])
    for slot in agreeing:  # then: an expression becomes the formula, else the number
        if slot.element is None or slot.text is None:
            continue
        definition = _definition(slot, name, target, files)
        if isinstance(definition, str):
            return definition
        chosen = _chosen_by_arguments(slot, name, files) if definition is None else None
        if chosen is not None:
            return chosen
        place = definition if definition is not None else slot.element
        attribute = "value" if definition is not None else slot.attribute
        written = _formula(name, place, target, decision, files)
        if written is not None:
            return writer.set(place, attribute, written)
        lost = place.get(attribute)
        new = decision.texts[name]
        note_lost(writer, target, name, new, lost, Slot(place, attribute, slot.users))
        return writer.set(place, attribute, new)
    if not agreeing:
        return shared_words(slots[-1], name, target, files)
    return f"its {name} is not written in a place that can take a number"


def _formula(
    name: str, place: etree._Element, target: Target, decision: Decision, files: Files
) -> str | None:
    """The entry as a formula of the shape's dimensions and the kept mass, read where it is
    written (:mod:`.formulas`); ``None`` when the mass changes or the terms read elsewhere."""
    from inertia_kit.description.urdf.placement.formulas import formula

    inertial = target.link.inertial
    body = None if inertial is None else files.element(inertial.source)
    mass = None if body is None else child(body, "mass")
    if mass is None or "mass" in decision.changed or not _same_scope(place, mass, files):
        return None
    found = formula(name, target, decision, mass.get("value"), files)
    if found is None or not _same_scope(place, found[1], files):
        return None
    return found[0]


def _definition(slot: Slot, name: str, target: Target, files: Files) -> etree._Element | str | None:
    """
    The macro's own property that the slot reads whole (``${inertia_ixx}``), read nowhere
    else: editing its value keeps the property used. Defined in branches of a condition, the
    one the given arguments expand (:mod:`.conditionals`), or why it cannot be edited (a str).
    """
    from inertia_kit.description.urdf.placement import conditionals

    reference = None if slot.text is None else parameter_reference(slot.text)
    if reference is None or slot.element is None:
        return None
    found = conditionals.definitions(slot.element, reference)
    if not found:
        return None
    macro = enclosing_macro(found[0])
    if macro is None or uses(macro, reference) != 1:
        return None
    if not conditionals.conditional(found):
        return found[0]
    read = files.expanded(found, target.name, name)
    if read is not None:
        return read  # the branch these arguments expand; the others keep their own values
    branches = ", ".join(
        f"{files_location(d, files)}"
        + "".join(f" under {conditionals.written(c)}" for c in conditionals.conditions(d, macro))
        for d in found
    )
    return ArgumentsChoose(
        f"its {name} is read from property `{reference}`, defined in branches the arguments "
        f"choose ({branches}), and which one these arguments expand could not be told: write "
        "it in that branch"
    )


def _chosen_by_arguments(slot: Slot, name: str, files: Files) -> str | None:
    """Why the expression at the slot may not become a number: it reads an argument, or a
    property the arguments choose outside any macro, so other arguments read other values
    (the number would hold for all of them). ``None``: it may."""
    from inertia_kit.description.urdf.placement import conditionals

    text = slot.text or ""
    if slot.element is None:
        return None
    if "$(arg" in text:
        return ArgumentsChoose(
            f'its {name} is "{text}", read from an argument: a number written there would '
            "hold for every argument value; write it where the argument is given"
        )
    names = re.findall(r"[A-Za-z_]\w*", " ".join(_EXPRESSION.findall(text)))
    chosen = conditionals.chosen_by_arguments(slot.element, names)
    if chosen:
        where = "; ".join(
            f"{files_location(d, files)}"
            + "".join(f" under {conditionals.written(c)}" for c in conditionals.conditions(d))
            for d in chosen[:3]
        )
        return ArgumentsChoose(
            f'its {name} is "{text}", which reads properties the arguments choose ({where}): '
            "a number written there would hold for every argument value; write it where the "
            "argument is given, or in the branch these arguments expand"
        )
    return None


def files_location(element: etree._Element, files: Files) -> str:
    where = files.where(element)
    return "?" if where is None else location(where)


def note_lost(
    writer: Writer, target: Target, name: str, new: str, lost, slot: Slot, *, shape: bool = False
) -> None:
    """Say that ``lost`` (an expression at the slot, or the shape's ``<origin>`` text that
    does not read the same there) is written as the number ``new``."""
    if lost is None or not _expression(lost):
        return
    where = writer.files.where(slot.element) if slot.element is not None else None
    at = f" ({location(where)})" if where is not None else ""
    instead = (
        f'not as its shape\'s <origin> writes it ("{lost}": read in another scope there)'
        if shape
        else f'where "{lost}" was'
    )
    writer.notes.append(
        f"link `{target.name}` is no longer parametric: its {name} is written as {new}{at} "
        f"{instead}; its properties no longer change it"
    )


def shared_words(slot: Slot, name: str, target: Target, files: Files) -> str:
    where = files.where(slot.element) if slot.element is not None else None
    at = location(where) if where is not None else "its macro"
    names = ", ".join(f"`{u}`" for u in slot.users[:6]) + (", ..." if len(slot.users) > 6 else "")
    written = f'"{slot.text}" ' if slot.text is not None else ""
    why = f" ({slot.stop})" if slot.stop else ""
    return (
        f"its {name} is written {written}once ({at}) for {len(slot.users)} links ({names}) that "
        f"need different values{why}"
    )
