"""
Robot description text as XML, the way the URDF parsers read it: refused when empty or binary,
parsed safely (:mod:`.safexml`) with the slips TinyXML2 reads tolerated (:func:`fromstring`),
and every element's start tag located by line and column, which lxml does not give.
"""

from __future__ import annotations

import codecs
import functools
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

from lxml import etree

from inertia_kit.description.lines import from_libxml2, line_of, line_starts
from inertia_kit.description.safexml import (
    NO_ENTITIES,
    oversized,
    parser,
    refuse_entities,
    too_long,
)
from inertia_kit.errors import InputError

_BOM = b"\xef\xbb\xbf"
# UTF-16/32 by byte-order mark or by the NUL bytes around a leading "<" (XML 1.0, appendix F)
_WIDE_STARTS = (b"\xff\xfe", b"\xfe\xff", b"\x00\x00\xfe\xff", b"<\x00", b"\x00<", b"\x00\x00\x00<")
_SPACE = re.compile(rb"[ \t\r\n]*")
_VERSION_1 = re.compile(rb"""\bversion\s*=\s*["']1\.[0-9]+["']""")
_ENCODING = re.compile(rb"""\bencoding\s*=\s*["']([A-Za-z][A-Za-z0-9._-]*)["']""")
# Everything that starts with "<": comments, CDATA, processing instructions and the DOCTYPE are
# skipped whole, so the remaining lone "<" are the start tags, in document order ("<" cannot
# appear in attribute values or text).
_MARKUP = re.compile(
    rb"<!--.*?-->|<!\[CDATA\[.*?\]\]>|<\?.*?\?>|<!DOCTYPE(?:[^\[>]*\[.*?\])?[^>]*>|</|<", re.DOTALL
)
_NAME_END = re.compile(rb"[^\s/>]*")
_PREFIX = re.compile(r"[A-Za-z_][A-Za-z0-9._-]*")
_POSITION = re.compile(r",? line \d+, column \d+$")
#: The namespace a prefix used without a declaration is read in (``drake:`` in airo-models):
#: ``UNDECLARED + prefix``. No URDF tag is in it, as no URDF tag is in a declared ``drake:``.
UNDECLARED = "urn:inertia-kit:undeclared-prefix:"


def parse_xml(data: bytes, path: str | Path) -> etree._Element:
    """
    Parse XML safely: no network, no DTD loading, no entity expansion, no huge trees.

    Two slips that libxml2 refuses and TinyXML2 (urdfdom, so ROS, Gazebo and PyBullet) reads
    are tolerated, without moving any line or column: an XML declaration after blank lines or
    comments, or with a version other than 1.x (``<?xml version="0.0"?>``, common in
    pybullet_data), and NUL bytes after the end of the document.

    Raises ``InputError`` with the file, line and column of a syntax error, for an empty or
    binary file, and for any entity declaration.
    """
    check_text(data, path)
    refuse_entities(data, path)
    encoding = None
    if not _is_wide(data):
        data, encoding = _tolerate_declaration(data)
        end = len(data.rstrip(b"\x00\t\n\r "))
        if b"\x00" in data[end:]:
            data = data[:end]
    try:
        try:
            root = fromstring(data, remove_pis=True, encoding=encoding)
        except etree.XMLSyntaxError as error:
            if encoding is not None or "Unsupported encoding" not in str(error.msg):
                raise
            # an encoding libxml2 does not know: TinyXML2 (urdfdom, Gazebo, PyBullet, MuJoCo,
            # Drake) ignores the declaration and reads the bytes as UTF-8; so do we
            root = fromstring(data, remove_pis=True, encoding="utf-8")
    except LookupError:
        raise InputError(f"unsupported encoding {encoding!r}", path, 1) from None
    except etree.XMLSyntaxError as error:
        line, column = from_libxml2(data, *error.position) if error.position else (None, None)
        message = _POSITION.sub("", str(error.msg or error))
        raise InputError(f"not well-formed XML: {message}", path, line, column) from None
    except (ValueError, etree.LxmlError) as error:
        raise InputError(f"not XML: {error}", path) from None
    dtd = root.getroottree().docinfo.internalDTD
    if dtd is not None and next(iter(dtd.iterentities()), None) is not None:
        # only reachable for encodings the byte-level check cannot read (UTF-16, UTF-32)
        raise InputError(NO_ENTITIES, path, 1)
    _refuse_oversized(data, root, path)
    return root


def _refuse_oversized(data: bytes, root: etree._Element, path: str | Path) -> None:
    """``InputError`` (file, line, column) for a name or attribute value past the bounds of
    :func:`.safexml.oversized`."""
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        attributes = ((name.rpartition("}")[2], value) for name, value in element.items())
        what = oversized(element.tag.rpartition("}")[2], attributes)
        if what is not None:
            line, column = element_locator(data, root)(element)
            raise InputError(too_long(what), path, line, column)


def fromstring(data: bytes, **options: Any) -> etree._Element:
    """
    ``data`` parsed by a safe parser (:func:`.safexml.parser` with ``options``), with namespace
    prefixes that are used but never declared read as declared ones.

    TinyXML2 (urdfdom, so ROS and Gazebo), Drake and PyBullet know no namespaces: airo-models'
    ``<limit drake:acceleration="2.5">`` or ``<drake:collision_filter_group>`` without an
    ``xmlns:drake`` are plain names to them, and libxml2 refuses the file. Each such prefix is
    declared on the root element (``UNDECLARED + prefix``, after the root's name, so only the
    rest of that line moves; error columns there are moved back) and the file is parsed again,
    as strictly as any other: every other error is still one. Element positions are taken from
    the original bytes (:func:`start_tag_positions`), where ``prefix:name`` is what was written.

    Raises what ``etree.fromstring`` raises (``XMLSyntaxError`` with the line and column in the
    original bytes), and ``LookupError`` for an unknown ``encoding``.
    """
    safe = parser(**options)
    try:
        return etree.fromstring(data, safe, base_url=None)
    except etree.XMLSyntaxError as error:
        undeclared = any(e.type_name == "NS_ERR_UNDEFINED_NAMESPACE" for e in safe.error_log)
        declared = _declare(data, _prefixes(data, options)) if undeclared else None
        if declared is None:
            raise
        first = error
    data, (line, column), width = declared
    try:
        return etree.fromstring(data, parser(**options), base_url=None)
    except etree.XMLSyntaxError as error:
        if not error.position:
            raise first from None
        at_line, at_column = error.position
        if at_line == line and at_column > column:
            at_column -= width
        message = _POSITION.sub("", str(error.msg or error))
        raise etree.XMLSyntaxError(
            f"{message}, line {at_line}, column {at_column}", error.code, at_line, at_column
        ) from None


def _prefixes(data: bytes, options: dict[str, Any]) -> list[str]:
    """
    The prefixes of element and attribute names that a recovering parse leaves unresolved
    (``drake`` of ``drake:acceleration``): the names libxml2 found no declaration for. Only
    names are taken from this parse; the tree comes from a strict one.
    """
    found: set[str] = set()
    try:
        root = etree.fromstring(data, parser(recover=True, **options), base_url=None)
    except (etree.LxmlError, ValueError):
        return []
    if root is None:
        return []
    for element in root.iter():
        if not isinstance(element.tag, str):
            continue
        names = [element.tag, *element.attrib]
        found.update(name.partition(":")[0] for name in names if ":" in name and "{" not in name)
    return sorted(p for p in found if _PREFIX.fullmatch(p) and p.lower() not in ("xml", "xmlns"))


def _declare(data: bytes, prefixes: list[str]) -> tuple[bytes, tuple[int, int], int] | None:
    """
    ``data`` with ``xmlns:prefix`` declarations inserted after the root element's name, the
    (line, column) of the insertion and its width; ``None`` when there is nothing to declare or
    the bytes are not ASCII-compatible (UTF-16, UTF-32).
    """
    if not prefixes or _is_wide(data):
        return None
    root = next((m for m in _MARKUP.finditer(data) if m.end() - m.start() == 1), None)
    if root is None:
        return None
    at = _NAME_END.match(data, root.end()).end()
    inserted = "".join(f' xmlns:{p}="{UNDECLARED}{p}"' for p in prefixes).encode("ascii")
    line_start = data.rfind(b"\n", 0, at) + 1
    position = (data.count(b"\n", 0, at) + 1, at - line_start + 1)
    return data[:at] + inserted + data[at:], position, len(inserted)


def check_text(data: bytes, path: str | Path) -> None:
    """Refuse an empty file and a binary one (a NUL byte before the end) with a plain message."""
    if _is_wide(data):
        return
    if not data.removeprefix(_BOM).strip(b"\x00\t\n\r "):
        raise InputError("empty file: not a robot description", path)
    nul = data.rstrip(b"\x00\t\n\r ").find(b"\x00")
    if nul >= 0:
        line = line_of(line_starts(data[:nul]), nul)
        raise InputError("binary file (it holds NUL bytes): not a robot description", path, line)


def start_tag_positions(
    data: bytes, root: etree._Element
) -> dict[etree._Element, tuple[int, int]] | None:
    """
    ``element -> (line, column)`` of the ``<`` of every element's start tag, both 1-based, the
    column in characters of the file's decoding (:func:`~.edits.source_encoding`); ``None``
    when the bytes cannot be matched to the tree (UTF-16).

    lxml's ``sourceline`` is the line where the start tag *ends*, wrong for a tag spread over
    several lines (and off by one past line 65535, libxml2 2.14), and it has no column at all.
    """
    from inertia_kit.description.edits import source_encoding

    encoding = "utf-8"
    if _is_wide(data):
        data = _transcoded(data)
        if data is None:
            return None
    else:
        # columns in the characters of the text edits are made in: a file declaring
        # ISO-8859-1 counts a byte a character, whatever UTF-8 its bytes may also read as
        encoding = source_encoding(data)[1]
        try:
            codecs.lookup(encoding)
        except LookupError:
            encoding = "utf-8"
    starts = [match.start() for match in _MARKUP.finditer(data) if match.end() - match.start() == 1]
    elements = [element for element in root.iter() if isinstance(element.tag, str)]
    if len(starts) != len(elements):
        return None
    lines = line_starts(data)
    positions: dict[etree._Element, tuple[int, int]] = {}
    # columns counted on from the previous element of the same line: a minified robot on one
    # line decoded from its start for each element was quadratic
    last_line, last_offset, last_column = 0, 0, 1
    for offset, element in zip(starts, elements, strict=True):
        name = _qualified_name(element)
        if not data.startswith(b"<" + name, offset):
            return None
        line = line_of(lines, offset)
        if line != last_line:
            last_line, last_column = line, 1
            last_offset = lines[line - 1] if line > 1 else len(_BOM) * data.startswith(_BOM)
        last_column += len(data[last_offset:offset].decode(encoding, "replace"))
        last_offset = offset
        positions[element] = (line, last_column)
    return positions


def _transcoded(data: bytes) -> bytes | None:
    """UTF-16 or UTF-32 ``data`` as UTF-8 (no mark); ``None`` when it does not decode."""
    for mark, encoding in (
        (b"\x00\x00\xfe\xff", "utf-32-be"),
        (b"\xff\xfe\x00\x00", "utf-32-le"),
        (b"\xff\xfe", "utf-16-le"),
        (b"\xfe\xff", "utf-16-be"),
        (b"\x00\x00\x00<", "utf-32-be"),
        (b"<\x00\x00\x00", "utf-32-le"),
        (b"<\x00", "utf-16-le"),
        (b"\x00<", "utf-16-be"),
    ):
        if data.startswith(mark):
            start = len(mark) if mark[0] != ord("<") and mark[-1] != ord("<") else 0
            try:
                return data[start:].decode(encoding).encode("utf-8")
            except UnicodeError:
                return None
    return None


def element_locator(
    data: bytes, root: etree._Element
) -> Callable[[etree._Element], tuple[int | None, int | None]]:
    """
    ``element -> (line, column)`` for the tree ``root`` parsed from ``data``: the start tag's
    ``<`` (:func:`start_tag_positions`); where the bytes cannot be matched to the tree, lxml's
    ``sourceline`` and the first ``<tag`` on that line.
    """
    positions = start_tag_positions(data, root)
    lines = data.split(b"\n")

    def position(element: etree._Element) -> tuple[int | None, int | None]:
        found = positions.get(element) if positions is not None else None
        if found is None:
            found = element.sourceline, _column(lines, element)
        return found

    return position


def _is_wide(data: bytes) -> bool:
    return data.startswith(_WIDE_STARTS)


@functools.cache
def reads_declared(encoding: str) -> bool:
    """
    Whether :func:`parse_xml` decodes a file by its declared ``encoding``: libxml2 knows it.
    One it does not know (``cp500``, ``latin-1`` as a name) is read as UTF-8, as TinyXML2 does.
    """
    try:
        fromstring(f'<?xml version="1.0" encoding="{encoding}"?><a/>'.encode("ascii"))
    except etree.XMLSyntaxError as error:
        return "Unsupported encoding" not in str(error.msg)
    except (ValueError, LookupError, UnicodeError):
        return False
    return True


def _tolerate_declaration(data: bytes) -> tuple[bytes, str | None]:
    """
    ``data`` with a misplaced or non-1.x XML declaration blanked to spaces (newlines kept, so
    positions hold), and the encoding it named; ``data`` unchanged when the declaration is fine.
    """
    start = len(_BOM) if data.startswith(_BOM) else 0
    position = _SPACE.match(data, start).end()
    while data.startswith(b"<!--", position):
        end = data.find(b"-->", position + 4)
        if end < 0:
            return data, None
        position = _SPACE.match(data, end + 3).end()
    if not data.startswith(b"<?xml", position) or data[position + 5 : position + 6] not in (
        b" ",
        b"\t",
        b"\r",
        b"\n",
        b"?",
    ):
        return data, None
    end = data.find(b"?>", position)
    if end < 0:
        return data, None
    declaration = data[position : end + 2]
    if position == start and _VERSION_1.search(declaration):
        return data, None
    encoding = _ENCODING.search(declaration)
    blank = bytes(b if b in b"\r\n" else 32 for b in declaration)
    return (
        data[:position] + blank + data[end + 2 :],
        None if encoding is None else encoding.group(1).decode("ascii"),
    )


def _qualified_name(element: etree._Element) -> bytes:
    """The element's name as written: ``prefix:local`` or ``local``."""
    name = element.tag.rpartition("}")[2]
    return (f"{element.prefix}:{name}" if element.prefix else name).encode("utf-8")


def _column(lines: list[bytes], element: etree._Element) -> int | None:
    """1-based column of ``<tag`` on the element's line, when the tags cannot be matched."""
    line = element.sourceline
    if line is None or not 0 < line <= len(lines) or not isinstance(element.tag, str):
        return None
    text = lines[line - 1]
    match = re.search(b"<" + re.escape(_qualified_name(element)) + rb"(?=[\s/>])", text)
    if match is None:
        return None
    prefix = text[: match.start()]
    if line == 1:
        prefix = prefix.removeprefix(_BOM)
    return len(prefix.decode("utf-8", "replace")) + 1
