"""
Robot descriptions in: a ``.urdf`` or xacro file, parsed safely, into the model with the source
location of every element. Raises :class:`~inertia_kit.errors.InputError` for anything that is
not a readable robot description; never a traceback.
"""

from __future__ import annotations

import bisect
import math
import re
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.safexml import NO_ENTITIES, parser, read_bounded, refuse_entities
from inertia_kit.errors import InputError

__all__ = [
    "load",
    "needs_expansion",
    "parse_xml",
    "read_bounded",
    "refuse_entities",
    "start_tag_positions",
]

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
# Anything xacro would change: without it, a file that declares the xacro namespace (as xacro's
# own output does) is plain URDF, and xacro would give it back unchanged
_XACRO_AT_WORK = re.compile(rb"<\s*xacro:|\$\{|\$\(")
# What urdfdom, Gazebo and Drake read as a number: ASCII digits only, no "1_000", no hex
_NUMBER = re.compile(r"\s*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\s*")


def needs_expansion(data: bytes) -> bool:
    """
    Whether a file must go through xacro: xacro by content *and* using it (macros, ``${}``,
    ``$()``). A file that only declares the namespace, as xacro's own output does, is URDF.
    """
    from inertia_kit.description.xacro_expand import is_xacro

    return is_xacro(data) and _XACRO_AT_WORK.search(data) is not None


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
    _check_text(data, path)
    refuse_entities(data, path)
    encoding = None
    if not _is_wide(data):
        data, encoding = _tolerate_declaration(data)
        end = len(data.rstrip(b"\x00\t\n\r "))
        if b"\x00" in data[end:]:
            data = data[:end]
    try:
        safe = parser(remove_pis=True, encoding=encoding)
    except LookupError:
        raise InputError(f"unsupported encoding {encoding!r}", path, 1) from None
    try:
        root = etree.fromstring(data, safe, base_url=None)
    except etree.XMLSyntaxError as error:
        line, column = error.position if error.position else (None, None)
        message = re.sub(r",? line \d+, column \d+$", "", str(error.msg or error))
        raise InputError(f"not well-formed XML: {message}", path, line, column) from None
    except (ValueError, etree.LxmlError) as error:
        raise InputError(f"not XML: {error}", path) from None
    dtd = root.getroottree().docinfo.internalDTD
    if dtd is not None and next(iter(dtd.iterentities()), None) is not None:
        # only reachable for encodings the byte-level check cannot read (UTF-16, UTF-32)
        raise InputError(NO_ENTITIES, path, 1)
    return root


def load(
    path: str | Path,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
) -> model.Robot:
    """
    Load a URDF or xacro robot description.

    Parameters
    ----------
    path : str or Path
      A ``.urdf``, ``.xacro`` or ``.urdf.xacro`` file; xacro is recognised by content.
    xacro_args : mapping, optional
      ``name -> value`` for ``$(arg name)``, as ``name:=value`` on xacro's command line.
    package_paths : iterable of paths
      Folders searched first for ``$(find pkg)`` and ``package://pkg`` (a package, or a folder
      of packages).

    Returns
    -------
    robot : Robot
      A fragment (a xacro file of macros and properties only) loads as a robot with no links
      and ``fragment=True``.

    Raises
    ------
    InputError
      For anything that is not a readable robot description: a missing, unreadable, empty,
      binary or oversized file, malformed XML, entity declarations, a root other than
      ``<robot>``, or anything xacro refuses. Missing meshes and non-numeric values are not
      errors: they are recorded on the model (``Mesh.problem``, ``Robot.invalid``).
    """
    from inertia_kit.description.packages import PackageResolver
    from inertia_kit.description.xacro_expand import expand, is_xacro

    path = Path(path)
    data = read_bounded(path)
    _check_text(data, path)
    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)

    xacro = is_xacro(data)
    if needs_expansion(data):
        expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver)
        if expanded.fragment:
            return _fragment(path, expanded.files)
        return Builder(path, expanded.source_of, resolver, tuple(expanded.files)).robot(
            expanded.root
        )

    root = parse_xml(data, path)
    if xacro and not any(isinstance(child.tag, str) for child in root):
        return _fragment(path, (str(path),))  # as expand() classes an empty xacro file
    positions = start_tag_positions(data, root)
    lines = data.split(b"\n")

    def source_of(element: etree._Element) -> model.Source:
        position = positions.get(element) if positions is not None else None
        if position is None:
            position = element.sourceline, _column(lines, element)
        return model.Source(str(path), *position)

    return Builder(path, source_of, resolver, (str(path),)).robot(root)


def _fragment(path: Path, files: Iterable[str]) -> model.Robot:
    return model.Robot(None, (), (), (), model.Source(str(path), 1), tuple(files), (), True)


# --- bytes -------------------------------------------------------------------------------------


def _is_wide(data: bytes) -> bool:
    return data.startswith(_WIDE_STARTS)


def _check_text(data: bytes, path: str | Path) -> None:
    """Refuse an empty file and a binary one (a NUL byte before the end) with a plain message."""
    if _is_wide(data):
        return
    if not data.removeprefix(_BOM).strip(b"\x00\t\n\r "):
        raise InputError("empty file: not a robot description", path)
    nul = data.rstrip(b"\x00\t\n\r ").find(b"\x00")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        raise InputError("binary file (it holds NUL bytes): not a robot description", path, line)


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


def start_tag_positions(
    data: bytes, root: etree._Element
) -> dict[etree._Element, tuple[int, int]] | None:
    """
    ``element -> (line, column)`` of the ``<`` of every element's start tag, both 1-based, the
    column in characters; ``None`` when the bytes cannot be matched to the tree (UTF-16).

    lxml's ``sourceline`` is the line where the start tag *ends*, wrong for a tag spread over
    several lines (and off by one past line 65535, libxml2 2.14), and it has no column at all.
    """
    if _is_wide(data):
        return None
    starts = [match.start() for match in _MARKUP.finditer(data) if match.end() - match.start() == 1]
    elements = [element for element in root.iter() if isinstance(element.tag, str)]
    if len(starts) != len(elements):
        return None
    newlines = [match.start() for match in re.finditer(b"\n", data)]
    positions: dict[etree._Element, tuple[int, int]] = {}
    for offset, element in zip(starts, elements, strict=True):
        name = _qualified_name(element)
        if not data.startswith(b"<" + name, offset):
            return None
        index = bisect.bisect_left(newlines, offset)
        line_start = newlines[index - 1] + 1 if index else len(_BOM) * data.startswith(_BOM)
        column = len(data[line_start:offset].decode("utf-8", "replace")) + 1
        positions[element] = (index + 1, column)
    return positions


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


class Builder:
    """Turns a parsed ``<robot>`` element tree into the model, recording every invalid number."""

    def __init__(
        self,
        path: Path,
        source_of: Callable[[etree._Element], model.Source],
        resolver,
        files: tuple[str, ...],
    ):
        self.path = path
        self.source_of = source_of
        self.resolver = resolver
        self.files = files
        self.invalid: list[model.Invalid] = []
        # to list invalid values in document order, whatever order they were read in
        self.order: dict[etree._Element, int] = {}
        self.located: dict[int, tuple[etree._Element, str]] = {}
        self.namespace: str | None = None  # the root's default namespace, if it declares one

    # --- children -------------------------------------------------------------------------

    def tag(self, element: etree._Element) -> str | None:
        """
        The URDF tag of ``element``: its name when it is in no namespace or in the root's
        default one (TinyXML, which urdfdom uses, ignores namespaces), else ``None``.
        """
        tag = element.tag
        if not isinstance(tag, str):
            return None
        if tag[:1] != "{":
            return tag
        namespace, _, local = tag[1:].partition("}")
        return local if namespace == self.namespace else None

    def children(self, element: etree._Element, tag: str) -> list[etree._Element]:
        return [child for child in element if self.tag(child) == tag]

    def child(self, element: etree._Element, tag: str) -> etree._Element | None:
        return next((child for child in element if self.tag(child) == tag), None)

    # --- numbers ------------------------------------------------------------------------

    def number(self, element: etree._Element | None, attribute: str) -> model.Number:
        if element is None:
            return None
        text = element.get(attribute)
        if text is None:
            return None
        value = float(text) if _NUMBER.fullmatch(text) else math.nan
        if not math.isfinite(value):
            return self.invalid_value(text, attribute, element)
        return value

    def vector(self, element: etree._Element | None, attribute: str, default=None) -> model.Vector:
        if element is None:
            return default
        text = element.get(attribute)
        if text is None:
            return default
        parts = text.split()
        values = tuple(float(p) if _NUMBER.fullmatch(p) else math.nan for p in parts)
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            return self.invalid_value(text, attribute, element)
        return values  # type: ignore[return-value]

    def invalid_value(self, text: str, attribute: str, element: etree._Element) -> model.Invalid:
        invalid = model.Invalid(text, attribute, self.source_of(element))
        self.invalid.append(invalid)
        self.located[id(invalid)] = (element, attribute)
        return invalid

    def origin(self, element: etree._Element | None) -> model.Origin:
        if element is None:
            return model.Origin()
        return model.Origin(
            self.vector(element, "xyz", (0.0, 0.0, 0.0)),
            self.vector(element, "rpy", (0.0, 0.0, 0.0)),
            self.source_of(element),
        )

    # --- elements -----------------------------------------------------------------------

    def robot(self, root: etree._Element) -> model.Robot:
        if isinstance(root.tag, str):
            self.namespace = etree.QName(root).namespace
        if self.tag(root) != "robot":
            source = self.source_of(root)
            tag = etree.QName(root).localname if isinstance(root.tag, str) else "?"
            raise InputError(
                f"the root element is <{tag}>, not <robot>: not a URDF robot description",
                source.path,
                source.line,
                source.column,
            )
        self.order = {element: index for index, element in enumerate(root.iter())}
        links, joints, materials = [], [], []
        extensions: list[model.Extension] = []
        for child in root:
            tag = self.tag(child)
            if tag == "link":
                links.append(self.link(child))
            elif tag == "joint":
                joints.append(self.joint(child))
            elif tag == "material":
                materials.append(model.Material(child.get("name", ""), self.source_of(child)))
            elif tag == "gazebo":
                extensions.append(self.extension(child))
        return model.Robot(
            root.get("name"),
            tuple(links),
            tuple(joints),
            tuple(materials),
            self.source_of(root),
            self.files,
            tuple(sorted(self.invalid, key=self.document_order)),
            extensions=tuple(extensions),
        )

    def extension(self, element: etree._Element) -> model.Extension:
        tags = tuple(
            (etree.QName(child).localname, (child.text or "").strip())
            for child in element
            if isinstance(child.tag, str)
        )
        return model.Extension(element.get("reference"), tags, self.source_of(element))

    def document_order(self, invalid: model.Invalid) -> tuple[int, int]:
        element, attribute = self.located[id(invalid)]
        attributes = list(element.attrib)
        return (
            self.order.get(element, len(self.order)),
            attributes.index(attribute) if attribute in attributes else 0,
        )

    def link(self, element: etree._Element) -> model.Link:
        inertial = self.child(element, "inertial")
        return model.Link(
            element.get("name", ""),
            None if inertial is None else self.inertial(inertial),
            tuple(self.shape(e, "visual") for e in self.children(element, "visual")),
            tuple(self.shape(e, "collision") for e in self.children(element, "collision")),
            self.source_of(element),
        )

    def inertial(self, element: etree._Element) -> model.Inertial:
        mass = self.child(element, "mass")
        inertia = self.child(element, "inertia")
        values = {name: self.number(inertia, name) for name in model.Inertial.TENSOR}
        return model.Inertial(
            self.origin(self.child(element, "origin")),
            self.number(mass, "value"),
            source=self.source_of(element),
            mass_source=None if mass is None else self.source_of(mass),
            inertia_source=None if inertia is None else self.source_of(inertia),
            **values,
        )

    def shape(self, element: etree._Element, kind: str) -> model.Shape:
        return model.Shape(
            kind,
            element.get("name"),
            self.origin(self.child(element, "origin")),
            self.geometry(self.child(element, "geometry"), element),
            self.source_of(element),
        )

    def geometry(self, element: etree._Element | None, owner: etree._Element) -> model.Geometry:
        if element is None:
            return model.Unknown(None, self.source_of(owner))
        shape = next((child for child in element if isinstance(child.tag, str)), None)
        if shape is None:
            return model.Unknown(None, self.source_of(element))
        source = self.source_of(shape)
        tag = self.tag(shape)
        if tag is None:  # an element of another namespace (<drake:...>)
            local = etree.QName(shape).localname
            return model.Unknown(f"{shape.prefix}:{local}" if shape.prefix else shape.tag, source)
        if tag == "box":
            return model.Box(self.vector(shape, "size"), source)
        if tag == "cylinder":
            return model.Cylinder(
                self.number(shape, "radius"), self.number(shape, "length"), source
            )
        if tag == "sphere":
            return model.Sphere(self.number(shape, "radius"), source)
        if tag == "capsule":
            return model.Capsule(self.number(shape, "radius"), self.number(shape, "length"), source)
        if tag == "mesh":
            filename = shape.get("filename", "")
            resolved, problem = self.resolver.resolve_uri(filename, Path(source.path).parent)
            return model.Mesh(
                filename,
                # only an existing file: a path that names nothing is in ``problem``
                None if resolved is None or problem is not None else str(resolved),
                self.vector(shape, "scale", (1.0, 1.0, 1.0)),
                source,
                problem,
            )
        return model.Unknown(tag, source)

    def joint(self, element: etree._Element) -> model.Joint:
        parent, child = self.child(element, "parent"), self.child(element, "child")
        limit, dynamics, mimic = (
            self.child(element, "limit"),
            self.child(element, "dynamics"),
            self.child(element, "mimic"),
        )
        axis = self.child(element, "axis")
        return model.Joint(
            element.get("name", ""),
            element.get("type", ""),
            None if parent is None else parent.get("link"),
            None if child is None else child.get("link"),
            self.origin(self.child(element, "origin")),
            None if axis is None else self.vector(axis, "xyz", (1.0, 0.0, 0.0)),
            None
            if limit is None
            else model.Limit(
                self.number(limit, "lower"),
                self.number(limit, "upper"),
                self.number(limit, "effort"),
                self.number(limit, "velocity"),
                self.source_of(limit),
            ),
            None
            if dynamics is None
            else model.Dynamics(
                self.number(dynamics, "damping"),
                self.number(dynamics, "friction"),
                self.source_of(dynamics),
            ),
            None
            if mimic is None
            else model.Mimic(
                mimic.get("joint", ""),
                self.number(mimic, "multiplier"),
                self.number(mimic, "offset"),
                self.source_of(mimic),
            ),
            self.source_of(element),
        )
