"""
Robots of many links, to check that every command stays linear in their number: a serial
``chain`` (each link the child of the one before: the deepest tree) or a ``star`` (every link a
child of the base: the widest), as URDF, or as xacro calling one macro per link.

Every link is a box with collision geometry; one in three declares a placeholder tensor (IN013,
IN020 and IN023, with unsafe fixes), one in three has no ``<inertial>`` (IN001, fill writes
one), the rest are right for their box. One element a line, indented by two spaces.
"""

from __future__ import annotations

from kit.moments import box_moments

SIZE = (0.1, 0.2, 0.3)
SHAPES = ("chain", "star")


def _inertial(index: int, indent: str) -> str:
    kind = index % 3
    if kind == 2:
        return ""
    ixx, iyy, izz = (1.0, 1.0, 1.0) if kind == 1 else box_moments(2.0, SIZE)
    return (
        f"{indent}<inertial>\n"
        f'{indent}  <mass value="2"/>\n'
        f'{indent}  <inertia ixx="{ixx:.6g}" ixy="0" ixz="0" iyy="{iyy:.6g}" iyz="0" '
        f'izz="{izz:.6g}"/>\n'
        f"{indent}</inertial>\n"
    )


def _link(name: str, index: int) -> str:
    return (
        f'  <link name="{name}">\n'
        + _inertial(index, "    ")
        + '    <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>\n'
        "  </link>\n"
    )


def _joint(parent: str, child: str, kind: str) -> str:
    return (
        f'  <joint name="j_{child}" type="{kind}">\n'
        f'    <parent link="{parent}"/><child link="{child}"/>\n'
        '    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>\n'
        '    <limit lower="-1" upper="1" effort="10" velocity="1"/>\n'
        "  </joint>\n"
    )


def _parent(shape: str, index: int) -> str:
    return "base" if shape == "star" or index == 1 else f"l{index - 1}"


def urdf(links: int, shape: str = "chain", joint: str = "revolute") -> str:
    """
    A URDF of ``links`` links (the base, welded to ``world``, and ``links - 1`` more), each on
    a ``joint`` of that type (``fixed``: one body of them all, for the engines; ``alternate``:
    every odd link welded, every even one on a revolute joint, so one big welded body meets
    thousands of moving joints).
    """
    parts = [
        '<?xml version="1.0"?>\n<robot name="big">\n',
        '  <link name="world"/>\n',
        '  <joint name="j_base" type="fixed"><parent link="world"/><child link="base"/></joint>\n',
        _link("base", 0),
    ]
    for index in range(1, links):
        kind = joint if joint != "alternate" else ("fixed" if index % 2 else "revolute")
        parts.append(_joint(_parent(shape, index), f"l{index}", kind))
        parts.append(_link(f"l{index}", index))
    parts.append("</robot>\n")
    return "".join(parts)


def xacro(links: int, shape: str = "chain") -> str:
    """The same robot as :func:`urdf`, one call of a macro per link (three macros: one per
    kind of ``<inertial>``)."""
    macro = (
        '  <xacro:macro name="part{kind}" params="name parent">\n'
        '    <joint name="j_${{name}}" type="revolute">\n'
        '      <parent link="${{parent}}"/><child link="${{name}}"/>\n'
        '      <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>\n'
        '      <limit lower="-1" upper="1" effort="10" velocity="1"/>\n'
        "    </joint>\n"
        '    <link name="${{name}}">\n'
        "{inertial}"
        '      <collision><geometry><box size="0.1 0.2 0.3"/></geometry></collision>\n'
        "    </link>\n"
        "  </xacro:macro>\n"
    )
    parts = [
        '<?xml version="1.0"?>\n<robot name="big" xmlns:xacro="http://www.ros.org/wiki/xacro">\n',
        *(macro.format(kind=kind, inertial=_inertial(kind, "      ")) for kind in range(3)),
        '  <link name="world"/>\n',
        '  <joint name="j_base" type="fixed"><parent link="world"/><child link="base"/></joint>\n',
        _link("base", 0),
    ]
    for index in range(1, links):
        parts.append(
            f'  <xacro:part{index % 3} name="l{index}" parent="{_parent(shape, index)}"/>\n'
        )
    parts.append("</robot>\n")
    return "".join(parts)


#: The xacro element limit a 5000-link robot needs (15 elements a link): ``--xacro-limit``.
XACRO_ELEMENTS = 200_000
