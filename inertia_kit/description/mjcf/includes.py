"""
One MJCF element tree from a model and the files it ``<include>``\\s, as MuJoCo assembles it:
each ``<include file>`` is replaced by the children of the included file's root, wherever it
stands; the file is found relative to the main model's folder (MuJoCo's rule), else relative
to the including file. Every element keeps the file, line and column it was written at.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.reads import digest, key
from inertia_kit.description.safexml import read_bounded
from inertia_kit.description.xmlparse import element_locator, parse_xml
from inertia_kit.errors import InputError

#: more included files than any model has: a bound against include bombs
MAX_INCLUDES = 2000


@dataclass
class Assembled:
    """The assembled tree, where each element was written, and every file read."""

    root: etree._Element
    sources: dict[etree._Element, model.Source] = field(default_factory=dict)
    files: list[str] = field(default_factory=list)
    reads: dict[str, str | None] = field(default_factory=dict)

    def source_of(self, element: etree._Element) -> model.Source:
        found = self.sources.get(element)
        if found is None:  # no element is made here: only a bug gets here
            return model.Source(self.files[0], element.sourceline)
        return found


def assemble(path: Path) -> Assembled:
    """The model at ``path`` with its includes spliced in; ``InputError`` for a file that is
    missing, unreadable, not XML, includes itself, or is not an MJCF file (root ``<mujoco>``)."""
    root, located = _parse(path)
    if not isinstance(root.tag, str) or etree.QName(root).localname != "mujoco":
        raise InputError("not an MJCF model: its root element is not <mujoco>", path, 1)
    assembled = Assembled(root)
    _record(assembled, path, root, located)
    _splice(assembled, root, path, path.parent, (key(path),))
    return assembled


def _parse(path: Path) -> tuple[etree._Element, Callable]:
    data = read_bounded(path)
    root = parse_xml(data, path)
    located = element_locator(data, root)
    return root, (data, located)


def _record(assembled: Assembled, path: Path, root: etree._Element, located) -> None:
    data, position = located
    assembled.files.append(str(path))
    real = key(path)
    seen = assembled.reads.get(real, digest(data))
    assembled.reads[real] = seen if seen == digest(data) else None
    for element in root.iter():
        assembled.sources[element] = model.Source(str(path), *position(element))


def _splice(
    assembled: Assembled,
    element: etree._Element,
    including: Path,
    main_folder: Path,
    chain: tuple[str, ...],
) -> None:
    for child in list(element):
        if not isinstance(child.tag, str):
            continue
        if etree.QName(child).localname != "include":
            _splice(assembled, child, including, main_folder, chain)
            continue
        source = assembled.source_of(child)
        name = child.get("file")
        if not name:
            raise InputError("<include> without a file", source.path, source.line, source.column)
        target = _find(name, main_folder, including.parent)
        if target is None:
            raise InputError(
                f"<include file={name!r}>: no such file (looked in {main_folder} and "
                f"{including.parent})",
                source.path,
                source.line,
                source.column,
            )
        if key(target) in chain:
            raise InputError(
                f"<include file={name!r}> includes itself", source.path, source.line, source.column
            )
        if len(assembled.files) >= MAX_INCLUDES:
            raise InputError(
                f"more than {MAX_INCLUDES} included files", source.path, source.line, source.column
            )
        root, located = _parse(target)
        _record(assembled, target, root, located)
        _splice(assembled, root, target, main_folder, (*chain, key(target)))
        position = element.index(child)
        element.remove(child)
        for offset, spliced in enumerate(list(root)):
            element.insert(position + offset, spliced)


def _find(name: str, main_folder: Path, including_folder: Path) -> Path | None:
    # the first that exists, as MuJoCo opens it: one that is no regular file (a named pipe, a
    # folder) is then refused by the read, saying what it is, not reported missing
    for folder in (main_folder, including_folder):
        candidate = folder / name
        if candidate.exists():
            return candidate
    return None
