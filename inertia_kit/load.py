"""
Robot descriptions in: a ``.urdf`` or xacro file, parsed safely, into the model with the source
location of every element. Raises :class:`~inertia_kit.errors.InputError` for anything that is
not a readable robot description; never a traceback.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from lxml import etree

from inertia_kit import model
from inertia_kit.errors import InputError

# larger than any real robot description (the biggest published ones are a few MB)
MAX_BYTES = 50 * 1024 * 1024

_ENTITY_DECLARATION = re.compile(rb"<!ENTITY", re.IGNORECASE)


def read_bounded(path: str | Path) -> bytes:
    """The bytes of ``path``, refusing files over :data:`MAX_BYTES` and unreadable ones."""
    try:
        with open(path, "rb") as stream:
            data = stream.read(MAX_BYTES + 1)
    except FileNotFoundError:
        raise InputError("no such file", path) from None
    except IsADirectoryError:
        raise InputError("is a directory, not a robot description", path) from None
    except OSError as error:
        raise InputError(f"cannot read: {error.strerror}", path) from None
    if len(data) > MAX_BYTES:
        raise InputError(
            f"file is larger than {MAX_BYTES // (1024 * 1024)} MB; no robot description is that big",
            path,
        )
    return data


def refuse_entities(data: bytes, path: str | Path) -> None:
    """Raise on entity declarations (billion laughs, external entities) before any parser sees them."""
    match = _ENTITY_DECLARATION.search(data)
    if match:
        line = data.count(b"\n", 0, match.start()) + 1
        raise InputError(
            "entity declarations are not allowed in a robot description "
            "(nothing was expanded or fetched)",
            path,
            line,
            match.start() - data.rfind(b"\n", 0, match.start()),
        )


def parse_xml(data: bytes, path: str | Path) -> etree._Element:
    """
    Parse XML safely: no network, no DTD loading, no entity expansion, no huge trees.

    Raises ``InputError`` with the file, line and column of a syntax error.
    """
    refuse_entities(data, path)
    parser = etree.XMLParser(
        resolve_entities=False, no_network=True, load_dtd=False, huge_tree=False, remove_pis=True
    )
    try:
        return etree.fromstring(data, parser, base_url=None)
    except etree.XMLSyntaxError as error:
        line, column = error.position if error.position else (None, None)
        message = re.sub(r",? line \d+, column \d+$", "", str(error.msg or error))
        raise InputError(f"not well-formed XML: {message}", path, line, column) from None
    except ValueError as error:
        raise InputError(f"not XML: {error}", path) from None


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
    """
    from inertia_kit.packages import PackageResolver

    path = Path(path)
    data = read_bounded(path)
    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)

    from inertia_kit.xacro_expand import is_xacro

    if is_xacro(data):
        from inertia_kit.xacro_expand import expand

        expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver)
        if expanded.fragment:
            return model.Robot(
                None, (), (), (), model.Source(str(path), 1), tuple(expanded.files), (), True
            )
        return Builder(path, expanded.source_of, resolver, tuple(expanded.files)).robot(
            expanded.root
        )

    root = parse_xml(data, path)
    lines = data.split(b"\n")

    def source_of(element: etree._Element) -> model.Source:
        return model.Source(str(path), element.sourceline, _column(lines, element))

    return Builder(path, source_of, resolver, (str(path),)).robot(root)


def _column(lines: list[bytes], element: etree._Element) -> int | None:
    """1-based column of ``<tag`` on the element's line (lxml reports lines only)."""
    line = element.sourceline
    if line is None or not 0 < line <= len(lines) or not isinstance(element.tag, str):
        return None
    index = lines[line - 1].find(b"<" + etree.QName(element).localname.encode())
    return None if index < 0 else len(lines[line - 1][:index].decode("utf-8", "replace")) + 1


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

    # --- numbers ------------------------------------------------------------------------

    def number(self, element: etree._Element | None, attribute: str) -> model.Number:
        if element is None:
            return None
        text = element.get(attribute)
        if text is None:
            return None
        try:
            value = float(text)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            invalid = model.Invalid(text, attribute, self.source_of(element))
            self.invalid.append(invalid)
            return invalid
        return value

    def vector(self, element: etree._Element | None, attribute: str, default=None) -> model.Vector:
        if element is None:
            return default
        text = element.get(attribute)
        if text is None:
            return default
        parts = text.split()
        try:
            values = tuple(float(p) for p in parts)
        except ValueError:
            values = ()
        if len(values) != 3 or not all(math.isfinite(v) for v in values):
            invalid = model.Invalid(text, attribute, self.source_of(element))
            self.invalid.append(invalid)
            return invalid
        return values  # type: ignore[return-value]

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
        if not isinstance(root.tag, str) or etree.QName(root).localname != "robot":
            source = self.source_of(root)
            tag = etree.QName(root).localname if isinstance(root.tag, str) else "?"
            raise InputError(
                f"the root element is <{tag}>, not <robot>: not a URDF robot description",
                source.path,
                source.line,
                source.column,
            )
        links, joints, materials = [], [], []
        for child in root:
            if not isinstance(child.tag, str):
                continue
            tag = etree.QName(child).localname
            if tag == "link":
                links.append(self.link(child))
            elif tag == "joint":
                joints.append(self.joint(child))
            elif tag == "material":
                materials.append(model.Material(child.get("name", ""), self.source_of(child)))
        return model.Robot(
            root.get("name"),
            tuple(links),
            tuple(joints),
            tuple(materials),
            self.source_of(root),
            self.files,
            tuple(self.invalid),
        )

    def link(self, element: etree._Element) -> model.Link:
        inertial = element.find("inertial")
        return model.Link(
            element.get("name", ""),
            None if inertial is None else self.inertial(inertial),
            tuple(self.shape(e, "visual") for e in element.findall("visual")),
            tuple(self.shape(e, "collision") for e in element.findall("collision")),
            self.source_of(element),
        )

    def inertial(self, element: etree._Element) -> model.Inertial:
        mass = element.find("mass")
        inertia = element.find("inertia")
        values = {name: self.number(inertia, name) for name in model.Inertial.TENSOR}
        return model.Inertial(
            self.origin(element.find("origin")),
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
            self.origin(element.find("origin")),
            self.geometry(element.find("geometry"), element),
            self.source_of(element),
        )

    def geometry(self, element: etree._Element | None, owner: etree._Element) -> model.Geometry:
        if element is None:
            return model.Unknown(None, self.source_of(owner))
        shape = next((child for child in element if isinstance(child.tag, str)), None)
        if shape is None:
            return model.Unknown(None, self.source_of(element))
        source = self.source_of(shape)
        tag = etree.QName(shape).localname
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
                None if resolved is None else str(resolved),
                self.vector(shape, "scale", (1.0, 1.0, 1.0)),
                source,
                problem,
            )
        return model.Unknown(tag, source)

    def joint(self, element: etree._Element) -> model.Joint:
        parent, child = element.find("parent"), element.find("child")
        limit, dynamics, mimic = (
            element.find("limit"),
            element.find("dynamics"),
            element.find("mimic"),
        )
        axis = element.find("axis")
        return model.Joint(
            element.get("name", ""),
            element.get("type", ""),
            None if parent is None else parent.get("link"),
            None if child is None else child.get("link"),
            self.origin(element.find("origin")),
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
