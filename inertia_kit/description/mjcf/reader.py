"""
An MJCF model into the robot model, as MuJoCo's compiler reads it: the assembled tree
(:mod:`.includes`), ``<default>`` classes (:mod:`.defaults`), the ``<compiler>`` (:mod:`.compiler`),
``<frame>``\\s, every orientation form (:mod:`.orientation`), ``fromto``, mesh assets with their
``scale``, ``refpos``/``refquat`` and ``inertia`` mode.

A ``<body>`` is a link; its parent joint stands for the body's ``<joint>``\\s (the first one's
type and name: ``hinge`` is ``revolute``, or ``continuous`` when unlimited, ``slide`` is
``prismatic``, ``ball`` ``spherical``, ``free`` ``floating``) or, without any, for the weld
to its parent (``fixed``). ``<worldbody>`` is the link ``world``. Bodies are in MuJoCo's order
(its body ids, ``world`` first).
"""

from __future__ import annotations

import dataclasses
import math
import re
from collections.abc import Iterator
from pathlib import Path

import numpy as np
from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.mjcf.compiler import Compiler, read_compiler
from inertia_kit.description.mjcf.defaults import MAIN, Defaults, local
from inertia_kit.description.mjcf.includes import Assembled, assemble
from inertia_kit.description.mjcf.orientation import FORMS, OrientationError, rotation
from inertia_kit.description.mjcf.replicate import expand_replicates
from inertia_kit.description.reads import key
from inertia_kit.errors import InputError
from inertia_kit.physics.frames import matrix_rpy, transform
from inertia_kit.physics.numbers import usable

_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_JOINT_TYPES = {"free": "floating", "ball": "spherical", "slide": "prismatic", "hinge": "revolute"}
_FROMTO_TYPES = ("capsule", "cylinder", "box", "ellipsoid")


def load_mjcf(path: str | Path) -> model.Robot:
    """
    Load an MJCF model (root ``<mujoco>``) with the files it includes.

    Raises
    ------
    InputError
      For anything MuJoCo would refuse to read as XML: a missing or unreadable file, malformed
      XML, a missing include, an unknown default class, an orientation given twice.
    """
    return _Reader(Path(path)).robot()


#: the shortest ``fromto`` MuJoCo accepts (``mjMINVAL``, mjCGeom::Compile)
MIN_FROMTO = 1e-15
#: models attached inside attached models, deeper than any real model nests them
MAX_ATTACH_DEPTH = 32


class _Reader:
    def __init__(self, path: Path, attaching: tuple[str, ...] = ()):
        self.path = path
        # the files of the models being attached around this one, outermost first
        self.attaching = (*attaching, key(path))
        self.assembled: Assembled = assemble(path)
        self.root = self.assembled.root
        self.source_of = self.assembled.source_of
        self.defaults = Defaults(self.root, self.source_of)
        self.compiler: Compiler = read_compiler(self.root, self.source_of)
        expand_replicates(self.assembled, self.compiler)
        self.invalid: list[model.Invalid] = []
        self.links: list[model.Link] = []
        self.joints: list[model.Joint] = []
        self.meshes = self._mesh_assets()
        self.models = {
            element.get("name", ""): self.path.parent / element.get("file", "")
            for asset in self.root
            if local(asset) == "asset"
            for element in asset
            if local(element) == "model"
        }

    # --- numbers ------------------------------------------------------------------------

    def numbers(
        self, element: etree._Element, attribute: str, text: str, count: int | None, scale=False
    ) -> tuple[float, ...] | model.Invalid:
        parts = text.split()
        values = tuple(float(p) if _NUMBER.fullmatch(p) else math.nan for p in parts)
        if (count is not None and len(values) != count) or not all(
            usable(v, scale) for v in values
        ):
            invalid = model.Invalid(text, attribute, self.source_of(element))
            self.invalid.append(invalid)
            return invalid
        return values

    def value(
        self, element: etree._Element, attribute: str, childclass: str, count: int | None = None
    ) -> tuple[tuple[float, ...] | model.Invalid | None, etree._Element | None]:
        """An attribute's numbers with its default classes, and where they are written."""
        found = self.defaults.lookup(element, attribute, childclass)
        if found is None:
            return None, None
        text, where = found
        return self.numbers(where, attribute, text, count), where

    def text(self, element: etree._Element, attribute: str, childclass: str, default=None):
        found = self.defaults.lookup(element, attribute, childclass)
        return default if found is None else found[0]

    # --- poses --------------------------------------------------------------------------

    def pose(self, element: etree._Element, childclass: str | None = None) -> np.ndarray:
        """The 4×4 pose ``pos`` and the orientation of ``element`` give (with classes when
        ``childclass`` is given: geoms and sites take them from defaults)."""
        matrix = np.eye(4)
        position = self._attribute(element, "pos", childclass, 3)
        if isinstance(position, tuple):
            matrix[:3, 3] = position
        forms = [f for f in FORMS if self._has(element, f, childclass)]
        if sum(element.get(f) is not None for f in forms) > 1:
            source = self.source_of(element)
            raise InputError(
                f"orientation given twice ({', '.join(forms)}): MuJoCo refuses it",
                source.path,
                source.line,
                source.column,
            )
        own = [f for f in forms if element.get(f) is not None]
        form = own[0] if own else (forms[0] if forms else None)
        if form is not None:
            values = self._attribute(element, form, childclass, None)
            if isinstance(values, tuple):
                try:
                    matrix[:3, :3] = rotation(
                        form,
                        values,
                        degrees=self.compiler.degrees,
                        eulerseq=self.compiler.eulerseq,
                    )
                except OrientationError as error:
                    source = self.source_of(element)
                    raise InputError(str(error), source.path, source.line, source.column) from None
        return matrix

    def _has(self, element, attribute, childclass) -> bool:
        if childclass is None:
            return element.get(attribute) is not None
        return self.defaults.lookup(element, attribute, childclass) is not None

    def _attribute(self, element, attribute, childclass, count):
        if childclass is None:
            text = element.get(attribute)
            return None if text is None else self.numbers(element, attribute, text, count)
        return self.value(element, attribute, childclass, count)[0]

    def origin(self, matrix: np.ndarray, element: etree._Element) -> model.Origin:
        xyz = tuple(float(v) for v in matrix[:3, 3])
        rpy = tuple(float(v) for v in matrix_rpy(matrix[:3, :3]))
        return model.Origin(xyz, rpy, self.source_of(element))  # type: ignore[arg-type]

    # --- the tree -----------------------------------------------------------------------

    def robot(self) -> model.Robot:
        worlds = [c for c in self.root if local(c) == "worldbody"]
        shapes: list[model.Shape] = []
        bodies: list[tuple[etree._Element, np.ndarray, str]] = []
        for world in worlds:
            for element, frame, childclass in self.members(world, np.eye(4), MAIN):
                if local(element) == "geom":
                    shapes.append(self.shape(element, frame, childclass))
                elif local(element) in ("body", "attach"):
                    bodies.append((element, frame, childclass))
        source = self.source_of(worlds[0]) if worlds else self.source_of(self.root)
        self.links.append(_link("world", None, shapes, source))
        for element, frame, childclass in bodies:
            self.child(element, "world", frame, childclass)
        self.invalid.sort(key=lambda i: (i.source.path, i.source.line or 0, i.source.column or 0))
        return model.Robot(
            name=self.root.get("model"),
            links=tuple(self.links),
            joints=tuple(self.joints),
            materials=(),
            source=self.source_of(self.root),
            files=tuple(self.assembled.files),
            invalid=tuple(self.invalid),
            fragment=not worlds,
            reads=tuple(self.assembled.reads.items()),
            format="mjcf",
            inference=self.compiler.inference,
            skeleton=self.musculoskeletal(),
        )

    def musculoskeletal(self) -> bool:
        """Whether muscles act on the model (``<muscle>``, or ``<general dyntype="muscle">``):
        then its geoms are bones, wrapping surfaces and skin, not the bodies' envelopes."""
        return any(
            local(element) == "muscle"
            or (
                local(element) == "general"
                and self.text(element, "dyntype", MAIN) == "muscle"  # from its class, too
            )
            for actuators in self.root
            if local(actuators) == "actuator"
            for element in actuators.iter()
        )

    def members(
        self, element: etree._Element, frame: np.ndarray, childclass: str
    ) -> Iterator[tuple[etree._Element, np.ndarray, str]]:
        """The children of a body (or the world), through ``<frame>``\\s: each with the pose
        of the frames around it and the childclass in force."""
        for child in element:
            tag = local(child)
            if tag == "frame":
                inner = frame @ self.pose(child)
                classes = child.get("childclass", childclass)
                yield from self.members(child, inner, self.defaults.check(classes, child))
            elif tag is not None:
                yield child, frame, childclass

    def body(self, element: etree._Element, parent: str, frame: np.ndarray, childclass: str):
        number = len(self.links)
        name = element.get("name") or f"body {number}"
        pose = frame @ self.pose(element)
        inner = self.defaults.check(element.get("childclass", childclass), element)
        inertial = None
        shapes: list[model.Shape] = []
        moves: list[etree._Element] = []
        children: list[tuple[etree._Element, np.ndarray, str]] = []
        for member, at, classes in self.members(element, np.eye(4), inner):
            tag = local(member)
            if tag == "inertial" and inertial is None:
                inertial = self.inertial(member, at)
            elif tag == "geom":
                shapes.append(self.shape(member, at, classes))
            elif tag in ("joint", "freejoint"):
                moves.append((member, classes))
            elif tag in ("body", "attach"):
                children.append((member, at, classes))
        source = self.source_of(element)
        self.links.append(_link(name, inertial, shapes, source))
        self.joints.append(self.joint(name, parent, pose, moves, element))
        for child, at, classes in children:
            self.child(child, name, at, classes)

    def child(self, element: etree._Element, parent: str, frame: np.ndarray, childclass: str):
        if local(element) == "body":
            self.body(element, parent, frame, childclass)
        else:
            self.attach(element, parent, frame)

    def attach(self, element: etree._Element, parent: str, frame: np.ndarray) -> None:
        """
        ``<attach model body prefix>``: the subtree of ``body`` in the ``<model>`` asset
        ``model`` (read with its own compiler, classes and assets), its names prefixed, hung
        from ``parent`` at the attach frame (the body keeps its pose relative to it).
        """
        source = self.source_of(element)
        wanted, prefix = element.get("body"), element.get("prefix", "")
        file = self.models.get(element.get("model", ""))
        if file is None or wanted is None:
            raise InputError(
                f"<attach>: no <model> asset named {element.get('model')!r} with a body",
                source.path,
                source.line,
                source.column,
            )
        if key(file) in self.attaching or len(self.attaching) >= MAX_ATTACH_DEPTH:
            why = "attaches itself" if key(file) in self.attaching else "attaches models too deep"
            raise InputError(
                f"<attach model={element.get('model')!r}>: {file} {why}",
                source.path,
                source.line,
                source.column,
            )
        other = _Reader(file, self.attaching).robot()
        if other.link(wanted) is None:
            raise InputError(
                f"<attach>: no body {wanted!r} in {file}", source.path, source.line, source.column
            )
        keep = {wanted}
        for joint in other.joints:  # in body order: a parent comes before its children
            if joint.parent in keep:
                keep.add(joint.child or "")
        self.invalid.extend(other.invalid)
        self.assembled.files.extend(f for f in other.files if f not in self.assembled.files)
        self.assembled.reads.update(other.reads)
        renamed = {name: prefix + name for name in keep}
        for link in other.links:
            if link.name in keep:
                self.links.append(dataclasses.replace(link, name=renamed[link.name]))
        for joint in other.joints:
            if joint.child not in keep:
                continue
            changes = {"name": prefix + joint.name, "child": renamed[joint.child]}
            if joint.child == wanted:
                pose = frame @ self.pose(element) @ _matrix(joint.origin)
                changes.update(parent=parent, origin=self.origin(pose, element))
            else:
                changes["parent"] = renamed[joint.parent]
            self.joints.append(dataclasses.replace(joint, **changes))

    # --- elements -----------------------------------------------------------------------

    def joint(self, body: str, parent: str, pose: np.ndarray, moves, element) -> model.Joint:
        origin = self.origin(pose, element)
        if not moves:
            return model.Joint(
                f"{body} (weld)",
                "fixed",
                parent,
                body,
                origin,
                None,
                None,
                None,
                None,
                self.source_of(element),
            )
        first, classes = moves[0]
        if local(first) == "freejoint":
            kind = "floating"
        else:
            written = self.text(first, "type", classes, "hinge")
            kind = _JOINT_TYPES.get(written, written)
            if kind == "revolute" and not self._limited(first, classes):
                kind = "continuous"
        axis = None
        if kind in ("revolute", "continuous", "prismatic"):
            found = self.value(first, "axis", classes, 3)[0]
            axis = found if found is not None else (0.0, 0.0, 1.0)
        return model.Joint(
            first.get("name") or f"{body} ({kind})",
            kind,
            parent,
            body,
            origin,
            axis,
            None,
            None,
            None,
            self.source_of(first),
        )

    def _limited(self, joint: etree._Element, classes: str) -> bool:
        limited = self.text(joint, "limited", classes, "auto")
        if limited == "auto":
            return self.compiler.autolimits and self.text(joint, "range", classes) is not None
        return limited == "true"

    def inertial(self, element: etree._Element, frame: np.ndarray) -> model.Inertial:
        turned = [f for f in FORMS if element.get(f) is not None]
        if element.get("fullinertia") is not None and turned:
            source = self.source_of(element)
            raise InputError(
                f"<inertial> with fullinertia and {turned[0]}: MuJoCo refuses an orientation "
                "with a full tensor",
                source.path,
                source.line,
                source.column,
            )
        matrix = frame @ self.pose(element)
        mass = self._attribute(element, "mass", None, 1)
        mass = mass[0] if isinstance(mass, tuple) else mass
        tensor: dict[str, model.Number] = dict.fromkeys(model.TENSOR, None)
        full = element.get("fullinertia")
        diagonal = element.get("diaginertia")
        if full is not None:
            values = self.numbers(element, "fullinertia", full, 6)
            if isinstance(values, tuple):
                tensor = dict(zip(("ixx", "iyy", "izz", "ixy", "ixz", "iyz"), values, strict=True))
            else:
                tensor = dict.fromkeys(model.TENSOR, values)
        elif diagonal is not None:
            values = self.numbers(element, "diaginertia", diagonal, 3, scale=True)
            if isinstance(values, tuple):
                tensor = {"ixx": values[0], "iyy": values[1], "izz": values[2]}
                tensor.update(ixy=0.0, ixz=0.0, iyz=0.0)
            else:
                tensor = dict.fromkeys(model.TENSOR, values)
        if full is None and diagonal is None:  # MuJoCo's default: a point mass
            tensor = dict.fromkeys(model.TENSOR, 0.0)
        source = self.source_of(element)
        return model.Inertial(
            origin=self.origin(matrix, element),
            mass=mass,
            source=source,
            mass_source=source,
            inertia_source=source,
            tensor_form="fullinertia" if full is not None else "diaginertia",  # or MuJoCo's 0
            **tensor,
        )

    def shape(self, element: etree._Element, frame: np.ndarray, classes: str) -> model.Shape:
        source = self.source_of(element)
        kind = self.text(element, "type", classes, "sphere")
        size, _ = self.value(element, "size", classes)
        fromto, _ = self.value(element, "fromto", classes, 6)
        pose = frame @ self.pose(element, classes)
        half_length = None
        if isinstance(fromto, tuple) and kind in _FROMTO_TYPES:
            start, end = np.array(fromto[:3]), np.array(fromto[3:])
            axis = start - end  # MuJoCo's z points from `to` to `from` (mjCGeom::Compile)
            try:
                if not np.linalg.norm(axis) > MIN_FROMTO:
                    raise OrientationError("fromto points too close in geom: MuJoCo refuses it")
                turn = rotation("zaxis", tuple(axis), degrees=False)
            except OrientationError as error:
                raise InputError(str(error), source.path, source.line, source.column) from None
            pose = frame.copy()
            pose[:3, 3] = frame[:3, :3] @ ((start + end) / 2) + frame[:3, 3]
            pose[:3, :3] = frame[:3, :3] @ turn
            half_length = float(np.linalg.norm(axis)) / 2
        size = size if isinstance(size, tuple) else ()
        mesh_name = self.text(element, "mesh", classes)
        if kind == "mesh" and mesh_name in self.meshes:
            geometry, reference = self.meshes[mesh_name]
            pose = pose @ reference
        elif kind == "mesh":
            geometry = model.Unknown(f"mesh {mesh_name!r}" if mesh_name else "mesh", source)
        elif mesh_name is not None:  # a primitive MuJoCo fits to the mesh
            fitscale, _ = self.value(element, "fitscale", classes, 1)
            scale = fitscale[0] if isinstance(fitscale, tuple) else 1.0
            geometry, placement = self.fitted(kind, self.meshes.get(mesh_name), scale, source)
            pose = pose @ placement
        else:
            geometry = self.primitive(kind, size, half_length, source)
        density, _ = self.value(element, "density", classes, 1)
        mass, _ = self.value(element, "mass", classes, 1)
        group, _ = self.value(element, "group", classes, 1)
        # None when nothing sets it: MuJoCo then weighs the geom at 1000 kg/m³
        density_value = density[0] if isinstance(density, tuple) else None
        mass_value = mass[0] if isinstance(mass, tuple) else None
        group_value = int(group[0]) if isinstance(group, tuple) else 0
        low, high = self.compiler.inference.groups
        weighs = (
            low <= group_value <= high
            and not isinstance(geometry, model.Unknown)
            and (mass_value if mass_value is not None else _or_default(density_value)) > 0
        )
        return model.Shape(
            "collision" if weighs else "visual",
            element.get("name"),
            self.origin(pose, element),
            geometry,
            source,
            density=density_value,
            mass=mass_value,
            shell=self.text(element, "shellinertia", classes, "false") == "true",
            group=group_value,
            collides=any(
                self.text(element, name, classes, "1").strip() not in ("0", "")
                for name in ("contype", "conaffinity")
            ),
        )

    def fitted(self, kind: str, asset, fitscale: float, source: model.Source):
        """
        The primitive MuJoCo fits to a mesh (``fitaabb="false"``, its default) and its pose in
        the geom's frame: sized by the mesh's equivalent inertia box, at its centre of mass in
        its principal axes (:func:`~inertia_kit.physics.mujoco_mesh_inertia.fitted_primitive`);
        an unknown geometry when the mesh cannot be read or is refused.
        """
        unknown = model.Unknown(f"{kind} fitted to a mesh", source), np.eye(4)
        if asset is None or self.compiler.fitaabb:
            return unknown
        mesh, reference = asset
        if mesh.path is None:
            return unknown
        from inertia_kit.physics.mujoco_mesh_inertia import file_fitted_primitive

        fitted = file_fitted_primitive(
            mesh.path, kind, mesh.inertia or "legacy", mesh.scale, fitscale
        )
        if fitted is None:
            return unknown
        size, centre, axes = fitted
        placement = np.eye(4)
        placement[:3, :3], placement[:3, 3] = axes, centre
        return self.primitive(kind, size, None, source), reference @ placement

    @staticmethod
    def primitive(kind, size, half_length, source) -> model.Geometry:
        """A primitive from MuJoCo's ``size`` (radii and half-lengths) or ``fromto``."""

        def get(index: int) -> float | None:
            return size[index] if len(size) > index else None

        if kind == "sphere":
            return model.Sphere(get(0), source)
        if kind == "capsule":
            half = half_length if half_length is not None else get(1)
            return model.Capsule(get(0), None if half is None else 2 * half, source)
        if kind == "cylinder":
            half = half_length if half_length is not None else get(1)
            return model.Cylinder(get(0), None if half is None else 2 * half, source)
        if kind == "box":
            half = half_length if half_length is not None else get(2)
            if get(0) is None or get(1) is None or half is None:
                return model.Box(None, source)
            return model.Box((2 * get(0), 2 * get(1), 2 * half), source)
        if kind == "ellipsoid":
            half = half_length if half_length is not None else get(2)
            if get(0) is None or get(1) is None or half is None:
                return model.Ellipsoid(None, source)
            return model.Ellipsoid((get(0), get(1), half), source)
        return model.Unknown(kind, source)

    def _mesh_assets(self) -> dict[str, tuple[model.Mesh, np.ndarray]]:
        """Mesh assets by name: the model's mesh and the pose of its file's frame in the
        geom's (``refpos``/``refquat``: vertices are read relative to that frame)."""
        folder = self.compiler.mesh_folder(self.path.parent)
        found_by = (
            "meshdir"
            if self.compiler.meshdir is not None
            else "assetdir"
            if self.compiler.assetdir is not None
            else "model folder"
        )
        meshes = {}
        for asset in (c for c in self.root if local(c) == "asset"):
            for element in (c for c in asset if local(c) == "mesh"):
                classes = MAIN
                name_file = self.text(element, "file", classes)
                source = self.source_of(element)
                name = element.get("name") or (Path(name_file).stem if name_file else None)
                if name is None:
                    continue
                scale, _ = self.value(element, "scale", classes, 3)
                mode = self.text(element, "inertia", classes, "legacy")
                path = None
                problem = "the mesh's vertices are written in the model, not read yet"
                rule, searched = None, ()
                if name_file is not None:
                    candidate = Path(name_file)
                    candidate = candidate if candidate.is_absolute() else folder / name_file
                    path = str(candidate) if candidate.is_file() else None
                    problem = None if path else f"no such file: {candidate}"
                    rule = "absolute path" if Path(name_file).is_absolute() else found_by
                    searched = () if path else (str(candidate),)
                written = scale if isinstance(scale, tuple) else (1.0, 1.0, 1.0)
                refpos, _ = self.value(element, "refpos", classes, 3)
                refquat, _ = self.value(element, "refquat", classes, 4)
                turn = np.eye(3)
                if isinstance(refquat, tuple):
                    try:
                        turn = rotation("quat", refquat, degrees=False)
                    except OrientationError as error:
                        raise InputError(
                            f"<mesh refquat>: {error}", source.path, source.line, source.column
                        ) from None
                # MuJoCo reads a vertex v as scale ⊙ Rᵀ(v - refpos): the same as the file scaled
                # by R·diag(scale)·Rᵀ, then turned by Rᵀ and moved, when that is a scale
                turned = turn @ np.diag(written) @ turn.T
                if np.abs(turned - np.diag(np.diag(turned))).max() > 1e-12 * np.abs(turned).max():
                    problem = "a refquat that turns a non-uniform scale is not read yet"
                    path = None
                    factors = (1.0, 1.0, 1.0)
                else:
                    factors = tuple(float(f) for f in np.diag(turned))
                placement = np.eye(4)
                placement[:3, :3] = turn.T
                if isinstance(refpos, tuple):
                    placement[:3, 3] = -(np.diag(written) @ turn.T @ np.array(refpos))
                mesh = model.Mesh(
                    name_file or name,
                    path,
                    factors,  # type: ignore[arg-type]
                    source,
                    problem=problem,
                    rule=rule if path else None,
                    searched=searched,
                    inertia=mode,
                )
                meshes[name] = (mesh, placement)
        return meshes


def _or_default(density: float | None) -> float:
    """A geom's density, MuJoCo's 1000 kg/m³ when nothing sets it."""
    return 1000.0 if density is None else density


def _matrix(origin: model.Origin) -> np.ndarray:
    return transform(origin.xyz, origin.rpy)


def _link(name, inertial, shapes, source) -> model.Link:
    return model.Link(
        name,
        inertial,
        tuple(s for s in shapes if s.kind == "visual"),
        tuple(s for s in shapes if s.kind == "collision"),
        source,
    )
