"""
The model from a parsed ``<robot>`` element tree, URDF or expanded xacro: each element to its
model type with its source location, numbers read as urdfdom reads them, and every value that
is not a usable number (not finite, or beyond what mass-property arithmetic can take:
:mod:`inertia_kit.physics.numbers`) recorded (``Robot.invalid``, in document order) instead of
raised.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable
from pathlib import Path

from lxml import etree

from inertia_kit.description import model
from inertia_kit.errors import InputError
from inertia_kit.physics.numbers import usable

# What urdfdom, Gazebo and Drake read as a number: ASCII digits only, no "1_000", no hex
_NUMBER = re.compile(r"\s*[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?\s*")
# Elements whose numbers are only compared, never multiplied: finite is enough (``1e16`` is a
# common "unlimited"); every other number must be usable in mass-property arithmetic
_COMPARED_ONLY = frozenset({"limit", "dynamics", "mimic"})
# values other values are divided by: a tiny one is unusable too (physics/numbers.py)
# what a second child of a <geometry> must be to be a second shape: URDF's, and those engines add
_SHAPES = frozenset({"box", "cylinder", "sphere", "mesh", "capsule", "ellipsoid", "plane", "cdf"})
_SCALES = frozenset({("mass", "value"), ("inertia", "ixx"), ("inertia", "iyy"), ("inertia", "izz")})


def _canonical(text: str | None) -> tuple | str | None:
    """A written value as compared: numbers by value (``0`` is ``0.0``), words as written."""
    if text is None:
        return None
    parts = text.split()
    if parts and all(_NUMBER.fullmatch(p) for p in parts):
        return tuple(float(p) for p in parts)
    return text.strip()


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
        # the link being read: its elements after the first where URDF allows one (link())
        self.duplicates: list[model.Duplicate] = []

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

    def single(
        self, element: etree._Element, tag: str, kind: str | None = None
    ) -> etree._Element | None:
        """
        The ``<tag>`` child the engines read where URDF allows one: the first, as urdfdom's
        TinyXML ``FirstChildElement``, Drake and PyBullet read it; each later one is recorded
        as a :class:`~inertia_kit.description.model.Duplicate` of the link being read.
        """
        found = self.children(element, tag)
        for extra in found[1:]:
            self.duplicate(found[0], extra, tag, self.tag(element) or "", kind)
        return found[0] if found else None

    def duplicate(
        self,
        read: etree._Element,
        extra: etree._Element,
        tag: str,
        parent: str,
        kind: str | None = None,
    ):
        mine, theirs = dict(self.written(read)), dict(self.written(extra))
        if parent == "geometry":  # two shapes: which shape is the first difference
            mine = {"shape": etree.QName(read).localname, **mine}
            theirs = {"shape": tag, **theirs}
        differences = tuple(
            (what, mine.get(what, "absent"), theirs.get(what, "absent"))
            for what in dict.fromkeys([*mine, *theirs])
            if _canonical(mine.get(what)) != _canonical(theirs.get(what))
        )
        self.duplicates.append(
            model.Duplicate(
                tag, parent, self.source_of(read), self.source_of(extra), differences, kind
            )
        )

    def written(self, element: etree._Element, prefix: str = "") -> list[tuple[str, str]]:
        """
        What an element says, as an engine reading it would: ``(what, text)`` for each of its
        attributes (``value`` named by its element alone: ``mass``) and, recursively, of the
        first child of each tag; a ``<geometry>``'s first shape only.
        """
        said = []
        for attribute, text in element.attrib.items():
            if attribute == "value":  # <mass value>: "mass"
                name = prefix or self.tag(element) or attribute
            else:
                name = f"{prefix} {attribute}".strip()
            said.append((name, text))
        children = [c for c in element if self.tag(c) is not None]
        if self.tag(element) == "geometry":
            children = children[:1]
            if children:
                said.append((f"{prefix} shape".strip(), self.tag(children[0]) or ""))
        seen: set[str] = set()
        for child in children:
            tag = self.tag(child) or ""
            if tag not in seen:
                seen.add(tag)
                said.extend(self.written(child, f"{prefix} {tag}".strip()))
        return said

    # --- numbers ------------------------------------------------------------------------

    def number(self, element: etree._Element | None, attribute: str) -> model.Number:
        if element is None:
            return None
        text = element.get(attribute)
        if text is None:
            return None
        value = float(text) if _NUMBER.fullmatch(text) else math.nan
        tag = self.tag(element)
        if not (
            usable(value, (tag, attribute) in _SCALES)
            or (math.isfinite(value) and tag in _COMPARED_ONLY)
        ):
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
        if len(values) != 3 or not all(usable(v) for v in values):
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
        self.duplicates = []
        inertial = self.single(element, "inertial")
        return model.Link(
            element.get("name", ""),
            None if inertial is None else self.inertial(inertial),
            tuple(self.shape(e, "visual") for e in self.children(element, "visual")),
            tuple(self.shape(e, "collision") for e in self.children(element, "collision")),
            self.source_of(element),
            tuple(self.duplicates),
        )

    def inertial(self, element: etree._Element) -> model.Inertial:
        mass = self.single(element, "mass")
        inertia = self.single(element, "inertia")
        values = {name: self.number(inertia, name) for name in model.Inertial.TENSOR}
        return model.Inertial(
            self.origin(self.single(element, "origin")),
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
            self.origin(self.single(element, "origin", kind)),
            self.geometry(self.single(element, "geometry", kind), element),
            self.source_of(element),
        )

    def geometry(self, element: etree._Element | None, owner: etree._Element) -> model.Geometry:
        if element is None:
            return model.Unknown(None, self.source_of(owner), absent=True)
        shapes = [child for child in element if isinstance(child.tag, str)]
        for extra in shapes[1:]:  # urdfdom, MuJoCo, Drake and PyBullet read the first shape
            local = etree.QName(extra).localname
            if local in _SHAPES:  # not a misplaced <material>, which is no second shape
                self.duplicate(shapes[0], extra, local, "geometry", self.tag(owner))
        shape = shapes[0] if shapes else None
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
            found = self.resolver.resolve(filename, Path(source.path).parent)
            return model.Mesh(
                filename,
                # only an existing file: a path that names nothing is in ``problem``
                None if found.path is None or found.problem is not None else str(found.path),
                self.vector(shape, "scale", (1.0, 1.0, 1.0)),
                source,
                found.problem,
                found.rule,
                found.searched,
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
