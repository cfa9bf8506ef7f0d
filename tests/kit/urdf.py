"""
Robot texts built one element at a time::

    robot(
        link("base"),
        joint("base", "arm"),
        link("arm", inertial(2, 0.01), collision(box(0.1, 0.2, 0.3))),
    )

Numbers are written as Python writes them (``f"{value}"``); a test that needs another spelling
(``"1e-4"``, ``"nan"``, six digits) passes a string. These builders write each element on one
line. ``moving`` and the ``*_lines`` builders write one element a line, for the tests that read
line and column numbers.
"""

from __future__ import annotations

from inertia_kit.physics.formatting import xml_number
from kit.moments import box_moments

LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'


def _triple(value) -> str:
    return value if isinstance(value, str) else " ".join(f"{v}" for v in value)


def origin(xyz=None, rpy=None) -> str:
    """``<origin>`` with the attributes given, or nothing when neither is."""
    given = (("xyz", xyz), ("rpy", rpy))
    attributes = "".join(f' {name}="{_triple(v)}"' for name, v in given if v is not None)
    return f"<origin{attributes}/>" if attributes else ""


def inertial(mass, ixx, iyy=None, izz=None, *, ixy=0, ixz=0, iyz=0, xyz=None, rpy=None) -> str:
    """
    ``<inertial>``: ``iyy`` and ``izz`` default to ``ixx`` (an isotropic tensor), the products
    to 0; the ``<origin>`` is written only when ``xyz`` or ``rpy`` is given.
    """
    iyy = ixx if iyy is None else iyy
    izz = ixx if izz is None else izz
    return (
        f'<inertial>{origin(xyz, rpy)}<mass value="{mass}"/>'
        f'<inertia ixx="{ixx}" ixy="{ixy}" ixz="{ixz}" iyy="{iyy}" iyz="{iyz}" izz="{izz}"/>'
        "</inertial>"
    )


def box_inertial(mass, size, *, xyz=None, rpy=None) -> str:
    """The ``<inertial>`` of a solid box of ``mass`` and ``size`` centred at ``xyz``."""
    return inertial(mass, *box_moments(mass, size), xyz=xyz, rpy=rpy)


# --- geometry --------------------------------------------------------------------------------


def box(x, y, z) -> str:
    return f'<box size="{x} {y} {z}"/>'


def cylinder(radius, length) -> str:
    return f'<cylinder radius="{radius}" length="{length}"/>'


def sphere(radius) -> str:
    return f'<sphere radius="{radius}"/>'


def mesh(filename, scale=None) -> str:
    attribute = "" if scale is None else f' scale="{_triple(scale)}"'
    return f'<mesh filename="{filename}"{attribute}/>'


def collision(geometry: str, *, xyz=None, rpy=None) -> str:
    return f"<collision>{origin(xyz, rpy)}<geometry>{geometry}</geometry></collision>"


def visual(geometry: str, *, xyz=None, rpy=None) -> str:
    return f"<visual>{origin(xyz, rpy)}<geometry>{geometry}</geometry></visual>"


# --- links, joints, robots -------------------------------------------------------------------


def link(name: str, *body: str) -> str:
    return f'<link name="{name}">{"".join(body)}</link>' if body else f'<link name="{name}"/>'


def joint(parent: str, child: str, kind: str = "revolute", *, name=None, xyz=None) -> str:
    """A joint named ``j_<child>`` unless ``name`` is given; all but a fixed one turn about z."""
    motion = "" if kind == "fixed" else f'<axis xyz="0 0 1"/>{LIMIT}'
    return (
        f'<joint name="{name or f"j_{child}"}" type="{kind}"><parent link="{parent}"/>'
        f'<child link="{child}"/>{origin(xyz)}{motion}</joint>'
    )


def robot(*parts: str, name: str = "r", sep: str = "") -> str:
    """The parts in a ``<robot>``, on one line, or one a line with ``sep="\\n"``."""
    return f'<robot name="{name}">{sep}' + sep.join(parts) + f"{sep}</robot>{sep}"


# --- one element a line ----------------------------------------------------------------------


def link_lines(name: str, mass=None, moment=None, *, indent: str = "  ", before: str = "") -> str:
    """A link, empty or holding ``mass`` with an isotropic ``moment``, one element a line."""
    if mass is None:
        return f'{indent}{before}<link name="{name}"/>\n'
    return (
        f'{indent}{before}<link name="{name}">\n'
        f"{indent}  <inertial>\n"
        f'{indent}    <mass value="{mass}"/>\n'
        f'{indent}    <inertia ixx="{moment}" ixy="0" ixz="0" iyy="{moment}" iyz="0" '
        f'izz="{moment}"/>\n'
        f"{indent}  </inertial>\n"
        f"{indent}</link>\n"
    )


def joint_lines(parent: str, child: str, kind: str = "revolute", *, name: str = "j") -> str:
    """A joint, one element a line; all but a fixed one turn about z."""
    motion = "" if kind == "fixed" else f'    <axis xyz="0 0 1"/>{LIMIT}\n'
    return (
        f'  <joint name="{name}" type="{kind}">\n'
        f'    <parent link="{parent}"/><child link="{child}"/>\n'
        f"{motion}"
        "  </joint>\n"
    )


def robot_lines(*parts: str, name: str = "r", head: str = "") -> str:
    """The ``*_lines`` parts in a ``<robot>``, after ``head`` (an XML declaration, a comment)."""
    return f'{head}<robot name="{name}">\n' + "".join(parts) + "</robot>\n"


def moving(body: str, extra: str = "", *, name="arm", kind="revolute", root="world") -> str:
    """
    A robot whose link ``name``, moving on a ``kind`` joint ``j`` from a massless ``root``, holds
    ``body`` on its line; ``extra`` is written after that link (more joints and links). The
    root is ``world`` (a fixed base): any other massless root above a moving link is IN001's.
    """
    return robot_lines(
        link_lines(root),
        joint_lines(root, name, kind),
        f'  <link name="{name}">{body}</link>{extra}\n',
    )


def as_written(values):
    """(mass, ixx, iyy, izz) as inertia-fill writes them: the mass to six significant digits
    and the moments scaled to that mass, as a second run computes them from the file."""
    m, ixx, iyy, izz = values
    written = float(xml_number(m, 6))
    return written, ixx * written / m, iyy * written / m, izz * written / m


def filled_inertial(values, com=(0, 0, 0), indent="  ", unit="  ", nl="\n", first=True) -> str:
    """
    The ``<inertial>`` block inertia-fill writes for ``values`` (mass, ixx, iyy, izz): one
    element a line, each line after ``indent`` (``first`` False leaves the first line bare),
    nested by ``unit``, numbers to six significant digits.
    """
    m, ixx, iyy, izz = as_written(values)
    n = lambda v: xml_number(v, 6)  # noqa: E731
    lines = [
        "<inertial>",
        f'{unit}<origin xyz="{" ".join(n(v) for v in com)}" rpy="0 0 0"/>',
        f'{unit}<mass value="{n(m)}"/>',
        f'{unit}<inertia ixx="{n(ixx)}" ixy="0" ixz="0" iyy="{n(iyy)}" iyz="0" izz="{n(izz)}"/>',
        "</inertial>",
    ]
    return nl.join((indent if first or i else "") + line for i, line in enumerate(lines))


#: one finding, IN002 (a negative mass) on `arm`, on the robot's one line; `base` is welded to
#: the world
NEGATIVE_MASS_ARM = robot(
    link("world"),
    joint("world", "base", "fixed"),
    link("base", inertial(1, 0.01)),
    joint("base", "arm"),
    link("arm", inertial(-1, 0.01)),
)
