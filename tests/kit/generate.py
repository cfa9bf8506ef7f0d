"""
Hypothesis strategies for robot descriptions nobody should write, and some they do: URDF and
xacro files whose numbers range over every float (NaN, ±inf, subnormals, ±1e308) and broken
texts, whose elements are missing, duplicated or unknown, in odd encodings, with mesh files
(closed, open, huge, tiny, empty, garbage) beside them.

:func:`cases` draws a :class:`Case`: the files of one robot description, written by
:meth:`Case.write` into a folder. Every text is built here, never by the code under test.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from hypothesis import strategies as st

from kit.meshes import ascii_stl, binary_stl, box_triangles, obj, square_triangles

# --- numbers --------------------------------------------------------------------------------

#: texts that have broken something, or sit on an edge (physics/numbers.py, IN004)
SPECIAL_NUMBERS = (
    "0", "-0", "1", "0.1", "-1", "1e-9", "1e308", "-1e308", "1.7976931348623157e308",
    "1e-320", "-1e-320", "5e-324", "2.2250738585072014e-308", "1e-307", "1e999", "-1e999",
    "1e50", "-1e50", "1e51", "1e-50", "1e-51", "1e-10", "9e-11", "1e16", "1e154", "1e155",
    "nan", "NaN", "-nan", "inf", "-inf", "Infinity", "abc", "", " ", "1,5", "2kg", "1.5.2",
    "+1", ".5", "5.", "1e", "0x10", "1_000", "١٢", " 1 ", "\t2\n",
)  # fmt: skip

_FLOATS = st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True)


def chance(percent: int) -> st.SearchStrategy[bool]:
    """
    True in about ``percent`` % of draws. Hypothesis draws the simplest value (0) far more
    often than its share, so that value means False: the rare case stays rare.
    """
    return st.sampled_from(range(100)).map(lambda i: i >= 100 - percent)


def _wild() -> st.SearchStrategy[str]:
    return st.one_of(
        _FLOATS.map(repr), _FLOATS.map(lambda x: f"{x:g}"), st.sampled_from(SPECIAL_NUMBERS)
    )


@st.composite
def numbers(draw) -> str:
    """
    The text of a numeric attribute: an ordinary value (0.001 to 1, as robots have) three times
    in four, else any float in any spelling, an edge of double precision, or a broken text.
    """
    if draw(chance(75)):
        return draw(st.floats(min_value=1e-3, max_value=1.0).map(lambda x: f"{x:.4g}"))
    return draw(_wild())


@st.composite
def vectors(draw) -> str:
    """Three numbers, usually; sometimes two or four, or separated by commas."""
    count = draw(st.sampled_from([3, 3, 3, 3, 3, 2, 4, 1]))
    parts = [draw(numbers()) for _ in range(count)]
    return draw(st.sampled_from([" ", " ", " ", ", ", "  "])).join(parts)


def _attribute(name: str, value: str | None) -> str:
    return "" if value is None else f' {name}="{_escape(value)}"'


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")


@st.composite
def maybe(draw, strategy, absent: float = 0.15):
    """A value of ``strategy``, or ``None`` (an attribute or element left out) now and then."""
    return None if draw(chance(round(absent * 100))) else draw(strategy)


# --- elements -------------------------------------------------------------------------------


@st.composite
def origins(draw) -> str:
    xyz, rpy = draw(maybe(vectors(), 0.4)), draw(maybe(vectors(), 0.6))
    if xyz is None and rpy is None and draw(st.booleans()):
        return ""
    return f"<origin{_attribute('xyz', xyz)}{_attribute('rpy', rpy)}/>"


MESH_NAMES = (
    "mesh0.stl", "mesh0.stl", "mesh1.obj", "mesh2.dae", "mesh3.ply", "missing.stl",
    "package://nopkg/x.stl", "file:///nonexistent/x.stl", "",
)  # fmt: skip


@st.composite
def geometries(draw) -> str:
    kind = draw(
        st.sampled_from(
            ["box", "box", "cylinder", "cylinder", "sphere", "capsule", "mesh", "mesh", "mesh",
             "unknown", "empty", "two", "none"]
        )
    )  # fmt: skip
    if kind == "none":
        return ""
    if kind == "empty":
        return "<geometry/>"
    if kind == "unknown":
        return "<geometry><foo size='1 1 1'/></geometry>"
    if kind == "two":
        return "<geometry><box size='0.1 0.1 0.1'/><sphere radius='0.1'/></geometry>"
    if kind == "box":
        shape = f"<box{_attribute('size', draw(maybe(vectors())))}/>"
    elif kind in ("cylinder", "capsule"):
        radius, length = draw(maybe(numbers())), draw(maybe(numbers()))
        shape = f"<{kind}{_attribute('radius', radius)}{_attribute('length', length)}/>"
    elif kind == "sphere":
        shape = f"<sphere{_attribute('radius', draw(maybe(numbers())))}/>"
    else:
        filename = draw(st.sampled_from(MESH_NAMES))
        scale = draw(maybe(st.one_of(vectors(), numbers()), 0.5))
        shape = f"<mesh{_attribute('filename', filename)}{_attribute('scale', scale)}/>"
    return f"<geometry>{shape}</geometry>"


@st.composite
def shapes(draw, kind: str) -> str:
    name = draw(st.sampled_from(["", ' name="s"']))
    return f"<{kind}{name}>{draw(origins())}{draw(geometries())}</{kind}>"


TENSOR = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


@st.composite
def inertials(draw) -> str:
    """An ``<inertial>``: any numbers, attributes or elements missing or twice."""
    plausible = draw(st.booleans())
    if plausible:  # a real-looking block, its numbers perturbed now and then
        values = {"ixx": "0.01", "iyy": "0.02", "izz": "0.015", "ixy": "0", "ixz": "0", "iyz": "0"}
        for name in draw(st.lists(st.sampled_from(TENSOR), max_size=2)):
            values[name] = draw(numbers())
        tensor = "".join(_attribute(name, values[name]) for name in TENSOR)
        mass = draw(st.one_of(st.just("1.5"), numbers()))
    else:
        tensor = "".join(_attribute(name, draw(maybe(numbers()))) for name in TENSOR)
        mass = draw(maybe(numbers()))
    parts = [draw(origins())]
    if mass is not None or draw(st.booleans()):
        parts.append(f"<mass{_attribute('value', mass)}/>")
    if not draw(chance(10)):
        parts.append(f"<inertia{tensor}/>")
    if draw(chance(5)):
        parts.append("<mass value='2'/>")
    return "<inertial>" + "".join(draw(st.permutations(parts))) + "</inertial>"


LINK_NAMES = ("base", "arm", "hand", "world", "a", "b", "", "base")
JOINT_TYPES = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar", "bogus", "")


@st.composite
def links(draw, name: str) -> str:
    body = []
    for _ in range(draw(st.sampled_from([0, 1, 1, 1, 2]))):
        body.append(draw(inertials()))
    for kind in ("visual", "collision"):
        for _ in range(draw(st.integers(0, 2))):
            body.append(draw(shapes(kind)))
    if draw(chance(10)):
        body.append("<sensor><noise>1e308</noise></sensor>")
    return f'<link name="{name}">' + "".join(body) + "</link>"


@st.composite
def joints(draw, names: list[str], index: int, chain: bool = False) -> str:
    """A joint: in a ``chain``, from link ``index`` to the next; else between any names."""
    if chain:
        parent, child = names[index], names[index + 1]
        kind = draw(st.sampled_from(("fixed", "revolute", "continuous", "prismatic")))
    else:
        candidates = [*names, "ghost"] if names else ["ghost"]
        parent, child = draw(st.sampled_from(candidates)), draw(st.sampled_from(candidates))
        kind = draw(st.sampled_from(JOINT_TYPES))
    parts = [f'<parent link="{parent}"/>', f'<child link="{child}"/>', draw(origins())]
    if draw(st.booleans()):
        parts.append(f"<axis{_attribute('xyz', draw(maybe(vectors())))}/>")
    if draw(st.booleans()):
        limit = "".join(
            _attribute(name, draw(maybe(numbers())))
            for name in ("lower", "upper", "effort", "velocity")
        )
        parts.append(f"<limit{limit}/>")
    if draw(chance(20)):
        parts.append(f"<dynamics{_attribute('damping', draw(numbers()))}/>")
    if draw(chance(10)):
        parts.append(f'<mimic joint="j0"{_attribute("multiplier", draw(numbers()))}/>')
    return f'<joint name="j{index}" type="{kind}">' + "".join(parts) + "</joint>"


@st.composite
def robot_bodies(draw) -> list[str]:
    """
    The elements of a ``<robot>``: a chain of links (most often), or links whose names may
    repeat and joints between any of them; and others.
    """
    if draw(chance(60)):
        names = ["base", *(f"l{i}" for i in range(draw(st.integers(0, 4))))]
        if draw(chance(10)):
            names[0] = "world"
        elements = [draw(links(name)) for name in names]
        elements += [draw(joints(names, i, chain=True)) for i in range(len(names) - 1)]
    else:
        names = draw(st.lists(st.sampled_from(LINK_NAMES), min_size=0, max_size=5))
        elements = [draw(links(name)) for name in names]
        elements += [draw(joints(names, i)) for i in range(draw(st.integers(0, len(names) + 1)))]
    if draw(chance(20)):
        elements.append('<gazebo reference="arm"><static>true</static><mu1>1e308</mu1></gazebo>')
    if draw(chance(10)):
        elements.append('<material name="m"><color rgba="nan 1 1 1"/></material><unknown/>')
    return elements


# --- xacro ----------------------------------------------------------------------------------

_XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


@st.composite
def xacro_bodies(draw) -> list[str]:
    """Robot elements with numbers passed through properties, expressions and a macro."""
    elements = draw(robot_bodies())
    value = draw(numbers())
    factor = draw(st.sampled_from(["1", "2", "1e300", "1e-300", "0", "-1"]))
    properties = [
        f'<xacro:property name="p" value="{_escape(value)}"/>',
        f'<xacro:property name="q" value="{factor}"/>',
        '<xacro:macro name="part" params="name mass:=1 size:=0.1">'
        '<link name="${name}"><inertial><mass value="${mass}"/>'
        '<inertia ixx="${mass*size*size/6}" ixy="0" ixz="0" iyy="${mass*size*size/6}" iyz="0" '
        'izz="${mass*size*size/6}"/></inertial>'
        '<collision><geometry><box size="${size} ${size} ${size}"/></geometry></collision>'
        "</link></xacro:macro>",
    ]
    calls = [
        draw(
            st.sampled_from(
                [
                    '<xacro:part name="m1"/>',
                    '<xacro:part name="m2" mass="${p}"/>',
                    '<xacro:part name="m3" size="${p*q}"/>',
                    '<xacro:part name="m4" mass="${q}" size="${p}"/>',
                    '<xacro:part name="${p}"/>',
                    '<xacro:if value="${q}"><link name="iffed"/></xacro:if>',
                ]
            )
        )
        for _ in range(draw(st.integers(0, 3)))
    ]
    substituted = [
        e.replace('value="1.5"', 'value="${p}"', 1).replace('ixx="0.01"', 'ixx="${p*q}"', 1)
        for e in elements
    ]
    return properties + substituted + calls


# --- files ----------------------------------------------------------------------------------

#: (declared encoding or None for no declaration, codec the bytes are written in)
ENCODINGS = (
    (None, "utf-8"),
    ("UTF-8", "utf-8"),
    ("UTF-8", "utf-8-sig"),
    ("utf-8", "latin-1"),
    ("ISO-8859-1", "latin-1"),
    ("shift_jis", "shift_jis"),
    ("shift_jis", "utf-8"),
    ("UTF-16", "utf-16"),
    ("UTF-16", "utf-8"),
    ("no-such-encoding", "utf-8"),
    ("ascii", "utf-8"),
    ("cp1252", "cp1252"),
)
COMMENTS = (
    "", "arm", "bras articulé", "ロボットの腕", "Ω ≤ 1e308", "\u2028", "--",
    "inertia-lint: ignore[IN004]", "inertia-lint: ignore[", "inertia-lint: disable-file",
    "inertia-lint: ignore[IN999, nonsense]",
)  # fmt: skip


def _mesh_files(draw) -> dict[str, bytes]:
    with np.errstate(over="ignore"):  # float32 makes 3.4e38 × 3 infinite: a file to read
        return _meshes(draw)


def _meshes(draw) -> dict[str, bytes]:
    size = draw(
        st.one_of(
            st.sampled_from([1.0, 0.1, 1e-3, 1e30, 1e-30, 1e38, 3.4e38, 1e-45]),
            st.floats(min_value=1e-6, max_value=10.0),
        )
    )
    triangles = box_triangles([size, size * 2, size * 3], low=[-size, 0, size])
    kind = draw(st.sampled_from(["binary", "ascii", "open", "inverted", "empty", "garbage"]))
    if kind == "binary":
        stl = binary_stl(triangles)
    elif kind == "ascii":
        text = ascii_stl(triangles)
        if draw(st.booleans()):
            broken = draw(st.sampled_from(["nan", "inf", "1e308"]))
            text = text.replace(repr(float(size)), broken, 1)
        stl = text.encode("ascii")
    elif kind == "open":
        stl = binary_stl(square_triangles() * size)
    elif kind == "inverted":
        stl = binary_stl(triangles[:, ::-1, :])
    elif kind == "empty":
        stl = b""
    else:
        stl = draw(st.binary(max_size=200))
    other = draw(st.sampled_from([b"", b"<COLLADA>", b"ply\nformat ascii 1.0\nend_header\n"]))
    return {
        "mesh0.stl": stl,
        "mesh1.obj": obj(np.asarray(triangles) * 1.0).encode("ascii"),
        "mesh2.dae": other if draw(st.booleans()) else draw(st.binary(max_size=100)),
        "mesh3.ply": other,
    }


@dataclass
class Case:
    """One robot description: ``main``, the file to lint, and every file beside it."""

    main: str
    files: dict[str, bytes] = field(default_factory=dict)

    def write(self, folder: Path) -> Path:
        for name, data in self.files.items():
            (folder / name).write_bytes(data)
        return folder / self.main


@st.composite
def cases(draw) -> Case:
    """A URDF or xacro file, and its meshes."""
    xacro = draw(st.booleans())
    body = draw(xacro_bodies() if xacro else robot_bodies())
    namespace = f" {_XACRO_NS}" if xacro or draw(chance(10)) else ""
    declared, codec = draw(st.sampled_from(ENCODINGS)) if draw(chance(30)) else ENCODINGS[1]
    declaration = "" if declared is None else f'<?xml version="1.0" encoding="{declared}"?>\n'
    comment = draw(st.sampled_from(COMMENTS)) if draw(chance(30)) else "a robot"
    text = (
        f'{declaration}<!-- {comment} -->\n<robot name="r"{namespace}>\n  '
        + "\n  ".join(body)
        + "\n</robot>\n"
    )
    data = text.encode(codec, errors="replace")
    if draw(chance(3)):
        data = data[: len(data) * draw(st.integers(1, 9)) // 10]  # a truncated file
    main = "robot.urdf.xacro" if xacro else draw(st.sampled_from(["robot.urdf", "robot.xacro"]))
    return Case(main, {main: data, **_mesh_files(draw)})
