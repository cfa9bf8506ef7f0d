"""
The files a fill may edit: read once, parsed once, only inside the input's package (the folder
holding the nearest ``package.xml``, else the input's folder) and only as the robot's load read
them (a file changed since is refused: :mod:`inertia_kit.description.reads`). Symbolic links
count where they point: an input that is a link is filled in the file it points to, within that
file's package; an included file that is a link into another package is not edited.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.description.edits import ChangedWhileEditing, Edit
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Robot, Source
    from inertia_kit.description.xmlspan import Span

#: Where an element is written: resolved path, line, column.
Key = tuple[str, int | None, int | None]


@dataclass
class Files:
    """The files edits may touch: read once, parsed once, and only inside ``root``."""

    root: Path
    sources: dict[str, SourceText] = field(default_factory=dict)
    # what the load read (description.reads): a file is edited only as the load read it
    reads: Mapping[str, str | None] = field(default_factory=dict)
    # the one file edits may touch, if only one: a robot read from stdin, whose fixed text is
    # printed (no other file is written, as a formatter reading stdin writes none)
    only: Path | None = None
    _elements: dict[str, dict[tuple[int, int], etree._Element]] = field(default_factory=dict)
    _positions: dict[int, tuple[str, int, int]] = field(default_factory=dict)  # id -> where
    _macros: dict[str, list[etree._Element]] | None = field(default=None, repr=False)
    _expanded: dict[tuple[int, ...], Robot | None] = field(default_factory=dict, repr=False)
    _real: dict[str, str] = field(default_factory=dict, repr=False)  # path -> real path
    # the robot loaded again, as the load did, under an overlay of changed texts
    # (:mod:`~inertia_kit.description.overlay`): how a fix tells which branch of a xacro
    # conditional the given arguments expand (:mod:`.conditionals`); ``None``: cannot tell
    reload: Callable[[], Robot] | None = None

    @classmethod
    def for_input(
        cls,
        path: str | Path,
        reads: Mapping[str, str | None] | None = None,
        *,
        only_itself: bool = False,
    ) -> Files:
        """The files a fix of the robot ``path`` may edit; ``reads``: what its load read;
        ``only_itself``: ``path`` alone (a robot read from stdin)."""
        path = Path(path).resolve()
        reads = {} if reads is None else reads
        only = path if only_itself else None
        for folder in path.parents:
            if os.path.isfile(folder / "package.xml"):
                return cls(folder, reads=reads, only=only)
        return cls(path.parent, reads=reads, only=only)

    def editable(self, path: str) -> bool:
        """Whether ``path`` is inside ``root`` (a symbolic link by the file it points to), is
        the one file of :attr:`only` when there is one, and can be read as text to edit."""
        return self._inside(path) and self._undecodable(path) is None

    def real(self, path: str | Path) -> str:
        """``path`` absolute, symbolic links resolved (``Path.resolve``): resolved once per
        path, for the many questions a plan asks of each file."""
        name = os.fspath(path)
        found = self._real.get(name)
        if found is None:
            found = self._real[name] = os.path.realpath(name)
        return found

    def key(self, source: Source) -> Key:
        """Where ``source`` is written (:data:`Key`), its path resolved once (:meth:`real`)."""
        return (self.real(source.path), source.line, source.column)

    def _inside(self, path: str) -> bool:
        resolved = Path(self.real(path))
        if self.only is not None:
            return resolved == self.only
        return resolved.is_relative_to(self.root)

    def _undecodable(self, path: str) -> str | None:
        """Why ``path`` cannot be read as text to edit (an encoding declared that its bytes
        are not: xacro read them as UTF-8), or ``None``."""
        try:
            self.source(path)
        except ChangedWhileEditing:
            raise
        except InputError as error:
            return error.message
        return None

    def outside(self, path: str) -> str:
        """``outside ROOT``, for a file :meth:`editable` refuses (naming a link's target), or
        why it cannot be edited as text."""
        # only a file inside is read to say why: a link's target outside is never opened
        undecodable = self._undecodable(path) if self._inside(path) else None
        if undecodable is not None:
            return f"not editable as text ({undecodable})"
        if self.only is not None:
            return "not the robot read from stdin (only its text is fixed and printed)"
        if os.path.islink(path):
            return f"outside {self.root} (it is a symbolic link to {Path(path).resolve()})"
        return f"outside {self.root}"

    def source(self, path: str) -> SourceText:
        """
        The text of ``path``, read once; ``ChangedWhileEditing`` when the load read other bytes
        there (the robot's lines and columns would point into another text).
        """
        from inertia_kit.description.reads import as_loaded

        resolved = self.real(path)
        if resolved not in self.sources:
            self.sources[resolved] = as_loaded(path, self.reads)
        return self.sources[resolved]

    def add(self, source: SourceText) -> None:
        """Use ``source`` for its path (the text a plan was made from)."""
        self.sources[self.real(source.path)] = source

    def offset(self, where: Source, tag: str) -> int | None:
        """The offset of the ``<`` of the element written at ``where`` (``None``: not found)."""
        from inertia_kit.description.lines import line_end

        if where.line is None:
            return None
        source = self.source(where.path)
        text = source.text
        try:
            line_start = source.offset(where.line)
        except ValueError:
            return None
        pattern = re.compile(r"<" + re.escape(tag) + r"(?=[\s/>])")
        if where.column is not None and pattern.match(text, line_start + where.column - 1):
            return line_start + where.column - 1
        found = [m.start() for m in pattern.finditer(text, line_start, line_end(text, line_start))]
        return found[0] if len(found) == 1 else None

    def span(self, where: Source, tag: str) -> tuple[SourceText, Span] | str:
        """
        The text and span of the element ``<tag>`` written at ``where``, to be edited; or why
        it cannot be: outside the files a fix may touch, or not found there.
        """
        from inertia_kit.description.xmlspan import element_span

        if not self.editable(where.path):
            return f"<{tag}> is written in {location(where)}, {self.outside(where.path)}"
        offset = self.offset(where, tag)
        if offset is None:
            return f"<{tag}> was not found at {location(where)}"
        source = self.source(where.path)
        return source, element_span(source.text, offset)

    def element(self, where: Source) -> etree._Element | None:
        """The parsed element written at ``where`` (for reading a macro's attributes)."""
        from inertia_kit.description.xmlparse import parse_xml, start_tag_positions

        resolved = self.real(where.path)
        if resolved not in self._elements:
            try:
                source = self.source(where.path)
                tree = parse_xml(source.original, where.path)
            except ChangedWhileEditing:
                raise
            except InputError:
                # xacro's parser read it, libxml2 (or the decoding for edits) does not: an
                # encoding declared that the bytes are not; its elements cannot be found, so no
                # fix is placed in it
                tree = None
            positions = {} if tree is None else start_tag_positions(source.original, tree) or {}
            self._elements[resolved] = {position: e for e, position in positions.items()}
            for element, (line, column) in positions.items():
                self._positions[id(element)] = (where.path, line, column)
        if where.line is None or where.column is None:
            return None
        return self._elements[resolved].get((where.line, where.column))

    def macros(self) -> dict[str, list[etree._Element]]:
        """``name -> <xacro:macro> elements`` defined in the files the load read, parsed once."""
        if self._macros is None:
            from inertia_kit.description.model import Source
            from inertia_kit.description.urdf.placement.xacro_macros import is_xacro

            self._macros = {}
            for path in self.reads:
                self.element(Source(path, None, None))  # parses it
                for element in self._elements.get(self.real(path), {}).values():
                    if is_xacro(element, "macro") and element.get("name"):
                        self._macros.setdefault(element.get("name"), []).append(element)
        return self._macros

    def expanded(
        self, candidates: Sequence[etree._Element], link: str, name: str
    ) -> etree._Element | None:
        """
        Which of ``candidates`` (``<xacro:property>`` definitions of one name) the load read
        for value ``name`` (``mass``, ``ixx``...) of ``link``: the robot loaded again with
        each given a stand-in value of its own. ``None``: none of them, or it cannot tell.
        """
        stand_ins = [f"0.{7310000 + index}13" for index in range(len(candidates))]
        robot = self._expanded_with(candidates, stand_ins)
        found = None if robot is None else next((k for k in robot.links if k.name == link), None)
        inertial = None if found is None else found.inertial
        value = None if inertial is None else getattr(inertial, name, None)
        if not isinstance(value, float):
            return None
        return next(
            (c for c, s in zip(candidates, stand_ins, strict=True) if value == float(s)), None
        )

    def _expanded_with(
        self, candidates: Sequence[etree._Element], values: Sequence[str]
    ) -> Robot | None:
        from inertia_kit.description.edits import apply_edits
        from inertia_kit.description.overlay import overlaid
        from inertia_kit.description.reads import key as key_of_read
        from inertia_kit.description.urdf.placement.writer import Writer

        cached = tuple(id(c) for c in candidates)
        if cached in self._expanded:
            return self._expanded[cached]
        robot = None
        writer = Writer(self)
        problems = [writer.set(c, "value", v) for c, v in zip(candidates, values, strict=True)]
        if self.reload is not None and not any(problems):
            texts = {}
            for path in {edit.path for edit in writer.result()}:
                source = self.source(path)
                mine = [edit for edit in writer.result() if edit.path == path]
                texts[key_of_read(path)] = source.encode(apply_edits(source.text, mine)[0])
            try:
                with overlaid(texts):
                    robot = self.reload()
            except InputError:  # the stand-ins broke the expansion: it cannot tell
                robot = None
        self._expanded[cached] = robot
        return robot

    def where(self, element: etree._Element) -> Source | None:
        """Where ``element`` (of a tree :meth:`element` parsed) is written."""
        from inertia_kit.description.model import Source

        found = self._positions.get(id(element))
        return None if found is None else Source(*found)

    def start(self, element: etree._Element) -> int | None:
        """The offset of the ``<`` of ``element`` (of a tree :meth:`element` parsed)."""
        found = self._positions.get(id(element))
        if found is None:
            return None
        path, line, column = found
        return self.source(path).offset(line, column)


def location(where: Source) -> str:
    """``path:line`` of an element, for messages."""
    return f"{where.path}:{where.line}" if where.line is not None else where.path


#: the rest of a start tag's line when nothing but blanks follows it
_LINE_REST = re.compile(r"[ \t]*(\r\n|\n|\r)")


def insert_first_child(source: SourceText, span: Span, block: str) -> Edit:
    """
    The edit that writes ``block`` (lines already indented, joined by the file's newline) as
    the first child of the element at ``span``: on the line after its start tag, or, when the
    element's content follows the start tag on its line, on lines of its own.
    """
    from inertia_kit.description.xmlspan import line_indent

    rest = _LINE_REST.match(source.text, span.start_tag_end)
    if rest is not None:
        return Edit(source.path, rest.end(), rest.end(), block + source.newline)
    after = source.newline + block + source.newline + line_indent(source.text, span.start)
    return Edit(source.path, span.start_tag_end, span.start_tag_end, after)
