"""
``<replicate count offset euler sep>`` expanded as MuJoCo expands it: ``count`` copies of its
children, copy ``i`` turned by ``euler`` × ``i`` (in the compiler's angle unit and sequence)
and moved by ``offset`` turned as each copy before it, each name in it given the suffix
``sep`` and ``i`` written with as many digits as ``count`` has (``b0``, ``b1``; ``b00`` …
``b11``); an inner replicate's suffix comes first. Each copy becomes a ``<frame>`` with that
pose, and every copied element keeps the place it was written at, so that a value written once
for all the copies is edited once.
"""

from __future__ import annotations

import copy

import numpy as np
from lxml import etree

from inertia_kit.description.mjcf.compiler import Compiler
from inertia_kit.description.mjcf.defaults import local
from inertia_kit.description.mjcf.includes import Assembled
from inertia_kit.description.mjcf.orientation import matrix_quat, rotation
from inertia_kit.errors import InputError

#: more copies than any model makes: a bound against a replicate bomb
MAX_COPIES = 100_000


def expand_replicates(assembled: Assembled, compiler: Compiler) -> None:
    """Replace every ``<replicate>`` of the assembled tree by its copies, innermost first."""
    made = [0]
    for element in [e for e in assembled.root.iter() if local(e) == "replicate"][::-1]:
        _expand(element, assembled, compiler, made)


def _numbers(element, attribute: str, default: str, assembled: Assembled) -> list[float]:
    text = element.get(attribute, default)
    try:
        values = [float(v) for v in text.split()]
    except ValueError:
        values = []
    if len(values) != len(default.split()) or not np.isfinite(values).all():
        source = assembled.source_of(element)
        raise InputError(
            f"<replicate {attribute}={text!r}>: not {len(default.split())} numbers",
            source.path,
            source.line,
            source.column,
        )
    return values


def _expand(element, assembled: Assembled, compiler: Compiler, made: list[int]) -> None:
    sources = assembled.sources
    source = assembled.source_of(element)
    count_text = element.get("count", "")
    if not count_text.strip().isdigit() or int(count_text) < 1:
        raise InputError(
            f"<replicate count={count_text!r}>: not a positive whole number",
            source.path,
            source.line,
            source.column,
        )
    count = int(count_text)
    made[0] += count * max(1, sum(1 for _ in element.iter()))
    if made[0] > MAX_COPIES:
        raise InputError(
            f"<replicate>s make more than {MAX_COPIES} elements", source.path, source.line
        )
    offset = np.array(_numbers(element, "offset", "0 0 0", assembled))
    euler = np.array(_numbers(element, "euler", "0 0 0", assembled))
    separator = element.get("sep", "")
    digits = len(str(count))
    parent = element.getparent()
    position = parent.index(element)
    position_i = np.zeros(3)
    for index in range(count):
        # copy i is turned by euler × i (the angles scaled, not the turn repeated) and moved
        # by the offsets turned as each copy before it is: MuJoCo 4.0, measured
        turn = rotation(
            "euler", euler * index, degrees=compiler.degrees, eulerseq=compiler.eulerseq
        )
        frame = etree.Element("frame")
        frame.set("pos", " ".join(repr(float(v)) for v in position_i))
        frame.set("quat", " ".join(repr(float(v)) for v in matrix_quat(turn)))
        position_i = position_i + turn @ offset
        sources[frame] = source
        suffix = separator + str(index).zfill(digits)
        for child in element:
            if not isinstance(child.tag, str):
                continue
            copied = copy.deepcopy(child)
            for original, duplicate in zip(child.iter(), copied.iter(), strict=True):
                if original in sources:
                    sources[duplicate] = sources[original]
                name = duplicate.get("name")
                if name is not None and isinstance(duplicate.tag, str):
                    duplicate.set("name", name + suffix)
            frame.append(copied)
        parent.insert(position + index, frame)
    parent.remove(element)
