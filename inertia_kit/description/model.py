"""
The robot model: frozen dataclasses for what a URDF says, each element with its source location.

Missing values stay ``None``, never a default: a made-up ``ixx = 1.0`` is exactly what the linter
exists to catch. A value that is present but not a usable number (not finite, beyond ±1e50, or
subnormal: :mod:`inertia_kit.physics.numbers`) is kept as :class:`Invalid`, with its location,
so one bad attribute does not hide every other finding.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from inertia_kit.physics.tensor_names import TENSOR

#: The link name Gazebo and the URDF importers read as the world itself, not a body.
WORLD = "world"


@dataclass(frozen=True)
class Source:
    """
    Where an element comes from: the file and line a person would edit.

    For an element a xacro macro produced, ``path``/``line`` are the element in the macro body
    and ``calls`` the macro calls that produced it, outermost first; :attr:`edit_site` picks the
    call site for values passed through macro parameters.
    """

    path: str
    line: int | None = None
    column: int | None = None
    calls: tuple[Source, ...] = ()

    @property
    def call_site(self) -> Source:
        """The outermost macro call that produced the element, or the element itself."""
        return self.calls[0] if self.calls else self

    def __str__(self) -> str:
        return ":".join(str(p) for p in (self.path, self.line, self.column) if p is not None)


@dataclass(frozen=True)
class Invalid:
    """
    A numeric attribute whose text is not a usable number (``abc``, ``nan``, ``inf``,
    ``1e308``, ``1e-320``).
    """

    text: str
    attribute: str
    source: Source


Number = float | Invalid | None
Vector = tuple[float, float, float] | Invalid | None


@dataclass(frozen=True)
class Origin:
    """A URDF ``<origin xyz rpy>``; absent attributes are zeros, as the URDF spec defines."""

    xyz: Vector = (0.0, 0.0, 0.0)
    rpy: Vector = (0.0, 0.0, 0.0)
    source: Source | None = None


@dataclass(frozen=True)
class Box:
    size: Vector
    source: Source


@dataclass(frozen=True)
class Cylinder:
    radius: Number
    length: Number
    source: Source


@dataclass(frozen=True)
class Sphere:
    radius: Number
    source: Source


@dataclass(frozen=True)
class Capsule:
    radius: Number
    length: Number
    source: Source


@dataclass(frozen=True)
class Ellipsoid:
    """An ellipsoid with semi-axes ``radii`` along x, y, z (MJCF's ``ellipsoid``)."""

    radii: Vector
    source: Source


@dataclass(frozen=True)
class Mesh:
    """
    A ``<mesh filename scale>``. ``path`` is the resolved file, or ``None`` when the URI did not
    resolve (``problem`` then says why). ``rule`` names the rule that found it (URDF's package
    resolution rules, :data:`~inertia_kit.description.urdf.package_lookup.RULES`; MJCF's
    ``meshdir``, ``assetdir`` or ``model folder``); ``searched`` lists the places looked at
    before (all of them when nothing was found).

    ``inertia`` is how the format's engine weighs the mesh when it infers mass properties from
    it (MJCF's ``<mesh inertia>``: ``legacy``, ``exact``, ``convex`` or ``shell``); ``None``:
    the solid the surface encloses (URDF).
    """

    filename: str
    path: str | None
    scale: Vector
    source: Source
    problem: str | None = None
    rule: str | None = None
    searched: tuple[str, ...] = ()
    inertia: str | None = None


@dataclass(frozen=True)
class Unknown:
    """
    A shape that is not one of URDF's: ``tag`` is the first element of the ``<geometry>``
    (``foo``, ``drake:capsule``), ``None`` when the ``<geometry>`` is empty or, with
    ``absent``, when the ``<visual>``/``<collision>`` has no ``<geometry>`` at all.
    """

    tag: str | None
    source: Source
    absent: bool = False


Geometry = Box | Cylinder | Sphere | Capsule | Ellipsoid | Mesh | Unknown


@dataclass(frozen=True)
class Shape:
    """
    A ``<visual>`` or ``<collision>``: a placed geometry. An MJCF ``<geom>`` is a ``collision``
    when MuJoCo counts it into the mass properties it infers (its ``group`` in the compiler's
    ``inertiagrouprange``, a positive ``mass`` or ``density``), else a ``visual``; ``density``
    (kg/m³, or kg/m² with ``shell``), ``mass`` and ``group`` are as the geom says, with its
    default classes (``None`` in URDF, which has none of them).
    """

    kind: str  # visual | collision
    name: str | None
    origin: Origin
    geometry: Geometry
    source: Source
    density: Number = None
    mass: Number = None
    shell: bool = False
    group: int | None = None
    #: whether it takes part in contacts (MJCF: ``contype`` or ``conaffinity`` not 0); ``None``
    #: where the element says it (URDF's collision and visual)
    collides: bool | None = None


@dataclass(frozen=True)
class Inertial:
    """
    A link's ``<inertial>``. ``mass`` and the six tensor values are ``None`` when absent (an
    ``<inertia>`` element missing, or one of its attributes missing).
    """

    origin: Origin
    mass: Number
    ixx: Number
    ixy: Number
    ixz: Number
    iyy: Number
    iyz: Number
    izz: Number
    source: Source
    mass_source: Source | None = None
    inertia_source: Source | None = None
    #: how the tensor is written where the format has several ways (MJCF: ``diaginertia`` or
    #: ``fullinertia``); ``None``: the format's one way (URDF's six attributes)
    tensor_form: str | None = None

    TENSOR = TENSOR

    def tensor_values(self) -> dict[str, Number]:
        return {name: getattr(self, name) for name in self.TENSOR}


@dataclass(frozen=True)
class Duplicate:
    """
    A second (third, ...) element where URDF allows one: a second ``<inertial>`` in a link, a
    second ``<mass>``, ``<inertia>`` or ``<origin>`` in an ``<inertial>``, a second ``<origin>``
    or ``<geometry>`` in a ``<visual>``/``<collision>``, a second shape (``<box>``, ``<mesh>``, ...;
    not any element: a misplaced ``<material>`` is no shape) in a ``<geometry>``.
    urdfdom (TinyXML ``FirstChildElement``), Drake and PyBullet read the first and ignore this
    one silently; MuJoCo refuses the file except for a second shape. ``differences`` are the
    values that differ, ``(what, read, ignored)`` as written (``("mass", "2", "5")``); empty
    when the two elements say the same.
    """

    tag: str  # the duplicated element's tag; a shape's is "shape"
    parent: str  # the element that holds both: link, inertial, visual, collision, geometry
    read: Source  # the element the engines read (the first)
    ignored: Source  # this one
    differences: tuple[tuple[str, str, str], ...] = ()
    kind: str | None = None  # visual or collision, for what is in or under one


@dataclass(frozen=True)
class Link:
    name: str
    inertial: Inertial | None
    visuals: tuple[Shape, ...]
    collisions: tuple[Shape, ...]
    source: Source
    # elements after the first where URDF allows one, which every reader but MuJoCo ignores
    duplicates: tuple[Duplicate, ...] = ()


@dataclass(frozen=True)
class Limit:
    lower: Number
    upper: Number
    effort: Number
    velocity: Number
    source: Source


@dataclass(frozen=True)
class Dynamics:
    damping: Number
    friction: Number
    source: Source


@dataclass(frozen=True)
class Mimic:
    joint: str
    multiplier: Number
    offset: Number
    source: Source


@dataclass(frozen=True)
class Joint:
    name: str
    type: str
    parent: str | None
    child: str | None
    origin: Origin
    axis: Vector  # None when absent: URDF then means (1, 0, 0)
    limit: Limit | None
    dynamics: Dynamics | None
    mimic: Mimic | None
    source: Source


@dataclass(frozen=True)
class Material:
    name: str
    source: Source


@dataclass(frozen=True)
class Extension:
    """
    A ``<gazebo>`` element (SDFormat's URDF extension): ``reference`` names a link or joint, or is
    ``None`` for the robot; ``tags`` are its child elements as (tag, text) pairs, in order.
    """

    reference: str | None
    tags: tuple[tuple[str, str], ...]
    source: Source

    def flag(self, tag: str) -> bool:
        """Whether ``<tag>`` is set to true (``true``, ``yes`` or ``1``, as sdformat reads it)."""
        return any(t == tag and v.strip().lower() in ("true", "yes", "1") for t, v in self.tags)


@dataclass(frozen=True)
class Inference:
    """
    How the format's engine makes mass properties of its own at load (MJCF's ``<compiler>``;
    URDF has none: ``Robot.inference`` is ``None``). ``from_geometry``: ``missing`` (a body
    without ``<inertial>`` gets its geoms': ``inertiafromgeom="auto"``), ``always`` (every
    body, the written values ignored: ``true``) or ``never`` (``false``); ``groups`` the geom
    groups counted (``inertiagrouprange``); ``min_mass`` and ``min_inertia`` the floors
    (``boundmass``, ``boundinertia``); ``balance`` whether impossible moments are raised to the
    triangle inequality (``balanceinertia``); ``total_mass`` the mass every body is scaled to
    (``settotalmass``, ``None`` when not set); ``fuse_static`` whether bodies without joints
    join their parents (``fusestatic``).
    """

    from_geometry: str = "missing"
    groups: tuple[int, int] = (0, 5)
    min_mass: float = 0.0
    min_inertia: float = 0.0
    balance: bool = False
    total_mass: float | None = None
    fuse_static: bool = False
    source: Source | None = None


@dataclass(frozen=True)
class Robot:
    """
    A robot description as loaded: links and joints in document order (names may repeat in a
    broken file, so they are tuples, not dicts), and the files it was read from.
    """

    name: str | None
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    materials: tuple[Material, ...]
    source: Source
    files: tuple[str, ...] = ()
    invalid: tuple[Invalid, ...] = field(default=())
    fragment: bool = False  # a xacro file with no link or joint (macros, properties): included
    extensions: tuple[Extension, ...] = ()  # <gazebo> elements, in document order
    # what the environment gave its xacro expansion ($(env), $(optenv), YAML values): kept out
    # of what is printed by --redact-env (description.redaction)
    environment_values: tuple[str, ...] = ()
    # (real path, digest of the bytes read) of every file read: what edits are computed on
    # (description.reads)
    reads: tuple[tuple[str, str | None], ...] = ()
    #: the format read: ``urdf`` (URDF or xacro) or ``mjcf``
    format: str = "urdf"
    #: how the format's engine infers mass properties nobody wrote (``None``: it does not)
    inference: Inference | None = None
    #: the geometry is a skeleton, not the bodies' envelope: a musculoskeletal model (muscles
    #: act on it), whose bodies carry flesh that no shape draws; their mass properties are not
    #: judged against their shapes
    skeleton: bool = False

    def link(self, name: str) -> Link | None:
        return next((link for link in self.links if link.name == name), None)

    def joint(self, name: str) -> Joint | None:
        return next((joint for joint in self.joints if joint.name == name), None)

    @property
    def roots(self) -> tuple[str, ...]:
        """Links that are no joint's child, in document order."""
        children = {joint.child for joint in self.joints}
        return tuple(link.name for link in self.links if link.name not in children)

    @property
    def root(self) -> str | None:
        """The root link, when there is exactly one."""
        roots = self.roots
        return roots[0] if len(roots) == 1 else None

    def parent_joint(self, link: str) -> Joint | None:
        return next((joint for joint in self.joints if joint.child == link), None)
