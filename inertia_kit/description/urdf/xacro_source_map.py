"""
The source map of a xacro expansion: every element stamped with the file, line and column it
was written at, and the stamps carried through macro expansion onto the URDF tree.

:func:`parse_stamped` parses a file with expat into minidom and stamps each element (DOM user
data under :data:`STAMP`, which minidom copies onto clones, so a macro body's stamps survive
its expansion); :func:`add_call_site` records a macro call on the elements it produced; and
:func:`serialise` and :func:`to_lxml` turn the expanded minidom tree into the lxml tree the loader
reads, with a map from each lxml element to its :class:`~inertia_kit.description.model.Source`.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any
from xml.dom import Node, UserDataHandler

from inertia_kit.description import safexml
from inertia_kit.description.lines import line_starts
from inertia_kit.description.model import Source
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from lxml import etree

#: The DOM user-data key of an element's stamp, a :class:`Source`.
STAMP = "inertia_kit.source"


class _CopyStampOnClone:
    """
    A DOM ``UserDataHandler``: a clone of a stamped node (a macro body) keeps its stamp.
    ``on_copy``, when set (by an expansion, for its element limit), is called for each copy.
    """

    on_copy: Callable[[], None] | None = None

    def handle(self, operation, key, data, src, dst) -> None:
        if dst is not None and operation in (
            UserDataHandler.NODE_CLONED,
            UserDataHandler.NODE_IMPORTED,
        ):
            dst.setUserData(key, data, self)
            if self.on_copy is not None:
                self.on_copy()


_COPY_STAMP = _CopyStampOnClone()


def stamp_of(node) -> Source | None:
    """Where the minidom element ``node`` was written, as stamped; ``None`` if unstamped."""
    return node.getUserData(STAMP)


def add_call_site(node, site: Source) -> None:
    """Prepend the macro call ``site`` to the ``calls`` of every stamped element under ``node``."""
    for element in _elements(node):
        source = element.getUserData(STAMP)
        if source is not None:
            stamp = dataclasses.replace(source, calls=(site, *source.calls))
            element.setUserData(STAMP, stamp, _COPY_STAMP)


def parse_stamped(data: bytes, shown: str, on_element: Callable[[], None] | None = None):
    """
    Parse with expat into minidom, every element stamped with ``Source(shown, line, col)``;
    ``on_element`` (an expansion's element limit) is called for each element as it is read.
    """
    from xml.dom import expatbuilder
    from xml.parsers import expat

    class Builder(expatbuilder.ExpatBuilderNS):
        def install(self, parser) -> None:
            super().install(parser)
            parser.EntityDeclHandler = self.refuse_entity
            parser.ExternalEntityRefHandler = self.refuse_entity

        def refuse_entity(self, *_args) -> None:
            raise InputError(safexml.NO_ENTITIES, shown, self._parser.CurrentLineNumber)

        def start_element_handler(self, name, attributes) -> None:
            super().start_element_handler(name, attributes)
            parser = self._parser
            source = Source(shown, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
            self.curNode.setUserData(STAMP, source, _COPY_STAMP)
            if on_element is not None:
                on_element()

    # xacro opens every file as text in Python's default encoding (UTF-8) and gives expat the
    # text, so expat ignores the declared encoding: the same here, from the bytes we checked
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as error:
        line = len(line_starts(data[: error.start]))
        raise InputError(_not_utf8(data, error), shown, line) from None
    try:
        return Builder().parseString(text)
    except expat.ExpatError as error:
        message = expat.ErrorString(error.code)
        if message == expat.errors.XML_ERROR_UNBOUND_PREFIX:
            # xacro (minidom) refuses it too; plain URDF reads it (see xmlparse.fromstring)
            message += (
                ": a namespace prefix is used without its `xmlns:` declaration, which xacro "
                'refuses; declare it on <robot> (`xmlns:drake="http://drake.mit.edu"`)'
            )
        raise InputError(
            f"not well-formed XML: {message}",
            shown,
            error.lineno,
            error.offset + 1,
        ) from None


_DECLARED_ENCODING = re.compile(rb"""^\s*<\?xml[^>]*?\bencoding\s*=\s*["']([^"']*)["']""")
_WIDE_MARKS = (b"\xff\xfe", b"\xfe\xff", b"<\x00", b"\x00<")


def _not_utf8(data: bytes, error: UnicodeDecodeError) -> str:
    """Why xacro cannot read ``data``, which is not UTF-8, and what to do."""
    if data.startswith(_WIDE_MARKS):
        what = "is UTF-16 or UTF-32"
    else:
        found = _DECLARED_ENCODING.match(data.removeprefix(b"\xef\xbb\xbf"))
        declared = (
            f', declared encoding="{found.group(1).decode("ascii", "replace")}"' if found else ""
        )
        what = f"is not UTF-8 (byte 0x{data[error.start]:02x}{declared})"
    return (
        f"{what}: xacro reads every file as UTF-8, whatever it declares, and fails on this "
        'one; save it as UTF-8 (and declare encoding="UTF-8")'
    )


def serialise(root, fallback: Source) -> tuple[str, list[Source]]:
    """
    The expanded minidom tree as XML text (attributes in document order, not xacro's sorted
    order) and the stamp of each element, in document order; :func:`to_lxml` reads them back.
    Plain values, so that an expansion run in a child process can hand them over.
    """
    out: list[str] = []
    sources: list[Source] = []
    _write(root, out, sources, fallback)
    return "".join(out), sources


def to_lxml(
    text: str, sources: list[Source], fallback: Source
) -> tuple[etree._Element, dict[Any, Source]]:
    """
    Parse :func:`serialise`'s text with lxml; pair elements in document order with
    ``sources`` to carry the stamps over.
    """
    from lxml import etree

    from inertia_kit.description.xmlparse import fromstring

    try:
        # xacro (minidom) knows no namespaces either: an undeclared `drake:` prefix passes it
        lxml_root = fromstring(text.encode("utf-8"), huge_tree=True)
    except etree.XMLSyntaxError as error:
        raise InputError(f"xacro produced XML lxml cannot read: {error}", fallback.path) from None
    elements = list(lxml_root.iter(etree.Element))
    if len(elements) != len(sources):  # pragma: no cover - serialisation is one-to-one
        raise InputError("internal error: expanded tree does not round-trip", fallback.path)
    return lxml_root, dict(zip(elements, sources, strict=True))


def _escape(text: str) -> str:
    """``xml.sax.saxutils.escape``: importing saxutils pulls in urllib, http, email and ssl
    (~20 ms), on every xacro expansion."""
    return text.replace("&", "&amp;").replace(">", "&gt;").replace("<", "&lt;")


def _quoteattr(value: str) -> str:
    """``xml.sax.saxutils.quoteattr``, as :func:`_escape`: escaped, white space kept, quoted."""
    value = _escape(value).replace("\n", "&#10;").replace("\r", "&#13;").replace("\t", "&#9;")
    if '"' not in value:
        return f'"{value}"'
    if "'" not in value:
        return f"'{value}'"
    return '"{}"'.format(value.replace('"', "&quot;"))


def _write(root, out: list[str], sources: list[Source], inherited: Source) -> None:
    """
    ``root`` as XML text into ``out`` (an explicit stack: a tree of any depth), refusing what a
    robot description may not hold (:func:`.safexml.oversized`, at the element's source) and a
    text larger than :data:`.safexml.MAX_BYTES`: the bounds apply to what an expansion returns,
    not only to the expansion (``name="${'x'*10**8}"`` is 230 bytes of xacro).
    """
    written = 0
    stack: list[tuple[Any, Source, bool]] = [(root, inherited, False)]
    while stack:
        node, inherited, closing = stack.pop()
        start = len(out)
        if closing:
            out.append(f"</{node.tagName}>")
        elif node.nodeType == Node.ELEMENT_NODE:
            source = node.getUserData(STAMP) or inherited
            attributes = node.attributes.items()
            what = safexml.oversized(node.tagName, attributes)
            if what is not None:
                raise InputError(f"xacro: {safexml.too_long(what)}", *_place(source))
            sources.append(source)
            out.append("<" + node.tagName)
            out.extend(f" {name}={_quoteattr(value)}" for name, value in attributes)
            if node.childNodes:
                out.append(">")
                stack.append((node, source, True))
                stack.extend((child, source, False) for child in reversed(node.childNodes))
            else:
                out.append("/>")
        elif node.nodeType in (Node.TEXT_NODE, Node.CDATA_SECTION_NODE):
            out.append(_escape(node.data))
        elif node.nodeType == Node.COMMENT_NODE:
            text = node.data.replace("--", "- -")
            out.append(f"<!--{text}{' ' if text.endswith('-') else ''}-->")
        written += sum(len(piece) for piece in out[start:])
        if written > safexml.MAX_BYTES:
            raise InputError(
                f"xacro: the expanded robot is larger than {safexml.size_text(safexml.MAX_BYTES)}"
                "; no robot description is that big (nothing was read further)",
                *_place(inherited),
            )


def _place(source: Source) -> tuple[str, int | None, int | None]:
    return source.path, source.line, source.column


def _elements(node) -> Iterator[Any]:
    """``node`` and its element descendants, document order."""
    stack = [node]
    while stack:
        current = stack.pop()
        if current.nodeType == Node.ELEMENT_NODE:
            yield current
            stack.extend(reversed(current.childNodes))
