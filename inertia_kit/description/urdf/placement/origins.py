"""
An ``<origin>`` value (``xyz``, ``rpy``) that the ``<inertial>`` does not write, and must: in
the body when every link made from it needs the same; else the body's macro gains optional
parameters (``origin_xyz:='0 0 0' origin_rpy:='0 0 0'``, xacro's default syntax), the body reads
them, and only the calls that need another origin pass one, as the shape writes it where it
reads the same (:func:`~inertia_kit.description.urdf.placement.attributes.text_at`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from inertia_kit.description.urdf.placement.attributes import (
    DEFAULT_ORIGIN,
    Decision,
    Slot,
    Writer,
    note_lost,
    shared_words,
    text_at,
    users_agree,
)
from inertia_kit.description.urdf.placement.xacro_macros import (
    child,
    enclosing_macro,
    parameter_names,
)

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.placement import Target


def write_origin(
    absent: list[str],
    body: etree._Element,
    target: Target,
    decisions: Mapping[str, Decision | None],
    users,
    writer: Writer,
) -> str | None:
    """Write ``xyz``/``rpy`` that the ``<inertial>`` does not write: in the body when every
    link made from it needs the same; else through new optional parameters of its macro,
    passed only at the calls that need another origin than ``0 0 0``."""
    inertial = target.link.inertial
    assert inertial is not None
    decision = decisions[target.name]
    assert decision is not None
    files = writer.files
    sharers = tuple(users.body[files.key(inertial.source)])
    origin = child(body, "origin")
    if all(users_agree(sharers, name, decisions) for name in absent):
        texts = {n: text_at(body, n, decision, sharers, decisions, files) for n in absent}
        for name, (new, lost) in texts.items():
            note_lost(writer, target, name, new, lost, Slot(body, name, sharers), shape=True)
        if origin is not None:
            for name, (new, _) in texts.items():
                problem = writer.set(origin, name, new)
                if problem is not None:
                    return problem
            return None
        written = {"xyz": DEFAULT_ORIGIN, "rpy": DEFAULT_ORIGIN}
        written |= {n: t for n, (t, _) in texts.items()}
        return writer.insert_first(body, f'<origin xyz="{written["xyz"]}" rpy="{written["rpy"]}"/>')
    macro = enclosing_macro(body)
    calls = inertial.source.calls
    call = None if not calls else files.element(calls[-1])
    if macro is None or call is None:
        return shared_words(Slot(body, absent[0], sharers), absent[0], target, files)
    made = tuple(users.chain.get(files.key(calls[-1]), ()))
    if not all(users_agree(made, name, decisions) for name in absent):
        return shared_words(Slot(call, absent[0], made), absent[0], target, files)
    # the same new parameters for every link the body makes, whichever asks first
    missing = [n for n in ("xyz", "rpy") if origin is None or origin.get(n) is None]
    taken = parameter_names(macro)
    names = {n: _free(f"origin_{n}", taken) for n in missing}
    declared = " ".join(f"{names[n]}:='{DEFAULT_ORIGIN}'" for n in missing)
    problem = writer.append(macro, "params", f" {declared}")
    if problem is None and origin is None:
        parts = {n: f"${{{names[n]}}}" if n in names else DEFAULT_ORIGIN for n in ("xyz", "rpy")}
        problem = writer.insert_first(body, f'<origin xyz="{parts["xyz"]}" rpy="{parts["rpy"]}"/>')
    elif problem is None:
        for name in missing:
            problem = problem or writer.set(origin, name, f"${{{names[name]}}}")
    for name in absent:
        if problem is not None:
            return problem
        new, lost = text_at(call, name, decision, made, decisions, files)
        note_lost(writer, target, name, new, lost, Slot(call, names[name], made), shape=True)
        problem = writer.set(call, names[name], new)
    return problem


def _free(name: str, taken: Mapping[str, bool]) -> str:
    """``name``, or ``inertial_xyz`` style, whichever the macro does not take yet."""
    for candidate in (name, name.replace("origin_", "inertial_"), name.replace("origin_", "com_")):
        if candidate not in taken:
            return candidate
    return f"{name}_"
