"""
Per-link analysis shared by report, lint and fill: each link with its place in the tree, its
declared mass properties, its geometry and the bounds that geometry sets, and the robot's
fixed-joint groups. Everything is computed on first use and kept, so rules that do not need
meshes never read them.
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

from inertia_kit.analysis.bounds import Hull, MomentExcess, moment_excess
from inertia_kit.analysis.declared import (
    declared,
    declared_mass,
    principal_moments,
    written_tensor,
)
from inertia_kit.analysis.geometry import (
    Geometry,
    MeshLoader,
    Solid,
    default_mesh_loader,
    evaluate_geometry,
)
from inertia_kit.description import model
from inertia_kit.physics.mass import MassProperties

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

    from inertia_kit.analysis.firmness import Firmness
    from inertia_kit.physics.meshes import MeshSolid


class LinkAnalysis:
    """A link with its place in the tree, its declared values and its geometry (lazily)."""

    def __init__(
        self,
        link: model.Link,
        parent: model.Joint | None,
        children: tuple[model.Joint, ...],
        load_mesh: MeshLoader = default_mesh_loader,
    ):
        self.link = link
        self.name = link.name
        self.parent = parent
        self.children = children
        self._load_mesh = load_mesh
        # the robot this link belongs to, set by RobotAnalysis (None for a link analysed alone)
        self.robot: RobotAnalysis | None = None

    @property
    def moves(self) -> bool:
        """Child of a non-fixed joint (revolute, continuous, prismatic, floating, planar)."""
        return self.parent is not None and self.parent.type != "fixed"

    @functools.cached_property
    def declared(self) -> MassProperties | None:
        return declared(self.link)

    @functools.cached_property
    def moments(self) -> NDArray[np.float64] | None:
        """
        (3,) ascending principal moments of the six ``<inertia>`` values alone, kg·m²: what
        the tensor rules judge when the mass or the ``<origin>`` is missing or not a number
        (the axes change no principal moment); ``None`` when a value is.
        """
        tensor = written_tensor(self.link)
        return None if tensor is None else principal_moments(tensor)

    @property
    def _summed(self) -> bool:
        # MuJoCo adds its geoms' values, overlaps and all: its model is compared with that
        return self.robot is not None and self.robot.robot.format == "mjcf"

    @functools.cached_property
    def collision(self) -> Geometry:
        return evaluate_geometry(
            self.link.collisions, "collision", self._load_mesh, summed=self._summed
        )

    @functools.cached_property
    def visual(self) -> Geometry:
        return evaluate_geometry(self.link.visuals, "visual", self._load_mesh, summed=self._summed)

    def mesh_kind_solids(self, kinds: tuple[str, ...] = ("visual", "collision")) -> Iterator[Solid]:
        """
        The solids of each of ``kinds`` (``visual``, ``collision``) that has at least one mesh
        shape; kinds without a mesh are not evaluated, so no mesh rule reads what it need not.
        """
        for kind in kinds:
            shapes = self.link.visuals if kind == "visual" else self.link.collisions
            if any(isinstance(s.geometry, model.Mesh) for s in shapes):
                yield from getattr(self, kind).solids

    @property
    def skeletal(self) -> bool:
        """Whether the link's shapes are a skeleton, not its envelope (``Robot.skeleton``)."""
        return self.robot is not None and self.robot.robot.skeleton

    @property
    def geometry(self) -> Geometry:
        """The geometry mass comes from: collision shapes, else visual ones; none for a
        skeleton's (its flesh is drawn by no shape)."""
        if self.skeletal:
            return Geometry(None, (), None)
        if self.link.collisions:
            return self.collision
        if self.link.visuals:
            return self.visual
        return Geometry(None, (), None)

    @functools.cached_property
    def envelope(self) -> Hull | None:
        """
        A convex set containing all the link's geometry, collision and visual: where its mass
        can be at most. ``None`` without geometry, or when any shape yields no solid (a partial
        envelope would understate what is possible).
        """
        kinds = [self.collision]
        if not self.visual.same_solids(self.collision):
            kinds.append(self.visual)  # the same solids twice make the same hull
        hulls = [g.hull for g in kinds if g.solids]
        if self.skeletal or not hulls or any(h is None for h in hulls):
            return None
        return Hull.union(hulls)  # type: ignore[arg-type]

    @functools.cached_property
    def excess(self) -> MomentExcess | None:
        """
        The declared tensor against the hard bound of :attr:`envelope` (see
        :func:`moment_excess`); ``None`` without a declared value or an envelope.
        """
        if self.declared is None or self.envelope is None:
            return None
        return moment_excess(self.declared, self.envelope)

    @functools.cached_property
    def firmness(self) -> Firmness | None:
        """
        How firm :attr:`excess` is when the declared tensor is beyond the bound (see
        :mod:`~inertia_kit.analysis.firmness`): an error only when it holds with every written
        number rounded in its favour, on collision geometry; ``None`` without an excess.
        """
        from inertia_kit.analysis.firmness import firmness

        return firmness(self)

    @property
    def mass_share(self) -> float:
        """The link's mass as a fraction of its fixed-joint group's (see RobotAnalysis)."""
        return 1.0 if self.robot is None else self.robot.mass_share(self.name)

    @functools.cached_property
    def bases(self) -> tuple[Geometry, ...]:
        """
        Every usable geometry of the link, collision first then visual: the shapes a rule may
        compare declared values with (one that matches either is not suspicious).
        """
        found = []
        if self.skeletal:
            return ()
        for shapes, name in ((self.link.collisions, "collision"), (self.link.visuals, "visual")):
            if shapes:
                geometry = getattr(self, name)
                if geometry.unit is not None and geometry.unit.mass > 0:
                    found.append(geometry)
        return tuple(found)

    @property
    def expected(self) -> MassProperties | None:
        """The geometry's mass properties for the declared mass (uniform density)."""
        if self.declared is None:
            return None
        return self.geometry.at_mass(self.declared.mass)


def _memoised(load_mesh: MeshLoader) -> MeshLoader:
    """One load per (mesh, scale) for one robot: visual and collision often name the same file."""
    from inertia_kit.errors import MeshError

    results: dict[tuple[str, tuple[float, float, float]], object] = {}

    def load(path: str, scale: tuple[float, float, float]) -> MeshSolid:
        key = (path, tuple(scale))
        if key not in results:
            try:
                results[key] = load_mesh(path, scale)
            except MeshError as error:
                results[key] = error
        result = results[key]
        if isinstance(result, MeshError):
            raise result
        return result  # type: ignore[return-value]

    return load


class RobotAnalysis:
    """All links of a robot, with tree relations and fixed-joint groups."""

    def __init__(self, robot: model.Robot, load_mesh: MeshLoader = default_mesh_loader):
        self.robot = robot
        load_mesh = _memoised(load_mesh)
        parents: dict[str, model.Joint] = {}
        children: dict[str, list[model.Joint]] = {}
        #: link -> every joint that names it as child (more than one: a broken tree, IN040's)
        self.joints_into: dict[str, list[model.Joint]] = {}
        for joint in robot.joints:
            if joint.child is not None:
                parents.setdefault(joint.child, joint)
                self.joints_into.setdefault(joint.child, []).append(joint)
            if joint.parent is not None:
                children.setdefault(joint.parent, []).append(joint)
        self.links = tuple(
            LinkAnalysis(
                link, parents.get(link.name), tuple(children.get(link.name, ())), load_mesh
            )
            for link in robot.links
        )
        self.by_name = {}
        for link in self.links:
            link.robot = self
            self.by_name.setdefault(link.name, link)
        self._groups: dict[str, tuple[LinkAnalysis, ...]] | None = None
        self._group_facts: dict[tuple[str, str], Any] = {}
        self._facts: dict[str, Any] = {}

    def group_of(self, name: str) -> tuple[LinkAnalysis, ...]:
        """
        The links welded to ``name`` by fixed joints, in either direction (what simulators lump
        into one body), ``name`` included; cycles and unknown names are tolerated. Each group
        is found once (for every link: a welded chain of 5000 links costs 5000 steps, not 5000
        walks of it), its links in the order of a walk from its first link in the file.
        """
        if self._groups is None:
            self._groups = self._fixed_groups()
        found = self._groups.get(name)
        if found is None:  # an unknown name
            return ()
        return found

    def _fixed_groups(self) -> dict[str, tuple[LinkAnalysis, ...]]:
        groups: dict[str, tuple[LinkAnalysis, ...]] = {}
        for first in self.links:
            if first.name in groups:
                continue
            seen: dict[str, LinkAnalysis] = {}
            stack = [first.name]
            while stack:
                current = stack.pop()
                if current in seen or current not in self.by_name:
                    continue
                link = self.by_name[current]
                seen[current] = link
                into = self.joints_into.get(current, ())
                stack.extend(j.parent for j in reversed(into) if j.type == "fixed" and j.parent)
                stack.extend(j.child for j in link.children if j.type == "fixed" and j.child)
            group = tuple(seen.values())
            for member in group:
                groups.setdefault(member.name, group)
        return groups

    def group_fact(
        self, name: str, fact: str, compute: Callable[[tuple[LinkAnalysis, ...]], Any]
    ) -> Any:
        """
        ``compute(group)`` for ``name``'s fixed-joint group, computed once per group and
        ``fact`` (its name): what each of a group's links asks costs one walk of the group.
        """
        group = self.group_of(name)
        key = (group[0].name if group else name, fact)
        if key not in self._group_facts:
            self._group_facts[key] = compute(group)
        return self._group_facts[key]

    def fact(self, name: str, compute: Callable[[RobotAnalysis], Any]) -> Any:
        """``compute(self)``, once per robot and ``name``: what several rules ask of all links."""
        if name not in self._facts:
            self._facts[name] = compute(self)
        return self._facts[name]

    def welded_to_world(self, name: str) -> bool:
        """Whether a fixed-joint path joins ``name`` to the link ``world`` (a static body)."""
        return self.group_fact(
            name, "welded to the world", lambda g: any(m.name == model.WORLD for m in g)
        )

    def mass_share(self, name: str) -> float:
        """
        The link's declared mass as a fraction of its fixed-joint group's (1.0 for a link alone
        or a group without mass): what its own values weigh in the body a simulator lumps.
        """
        link = self.by_name.get(name)
        mass = None if link is None else declared_mass(link.link)
        total = self.group_mass(name)
        if mass is None or total <= 0:
            return 1.0
        return mass / total

    def group_mass(self, name: str) -> float:
        """Total declared mass of ``name``'s fixed-joint group (finite positive masses only)."""
        return self.group_fact(
            name, "mass", lambda g: sum((declared_mass(link.link) or 0.0 for link in g), 0.0)
        )


def analyse(robot: model.Robot, load_mesh: MeshLoader = default_mesh_loader) -> RobotAnalysis:
    return RobotAnalysis(robot, load_mesh)
