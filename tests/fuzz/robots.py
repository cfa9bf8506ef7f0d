"""
Synthetic robots: URDF texts of any size and shape, and xacro projects that use every feature
the expansion offers (properties, macros with default and block parameters, includes relative
and through ``$(find)``, ``load_yaml``, ``$(arg)``, ``$(env)`` and ``$(optenv)``, conditionals,
``xacro:element``), with their meshes. Every draw comes from a ``random.Random``, so an input is
the same for the same seed; nothing here calls the code under test.
"""

from __future__ import annotations

import math
import random

from kit.generate import SPECIAL_NUMBERS

from fuzz import meshes
from fuzz.tree import Tree

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
SUPPRESSED = ("IN020", "IN013", "IN0", "IN999", "placeholder-inertia")
JOINT_TYPES = ("fixed", "revolute", "continuous", "prismatic", "floating", "planar")
#: the environment variable a ``$(env)`` reads; its value must never reach an output unasked
SECRET_VAR, SECRET = "FUZZ_SECRET_TOKEN", "s3cr3t-fuzz-value"


def number(rng: random.Random, low: float = 1e-3, high: float = 1.0) -> str:
    """An ordinary value nine times in ten, else an edge of double precision or a broken text."""
    if rng.random() < 0.9:
        return f"{rng.uniform(low, high):.{rng.choice([3, 4, 6, 17])}g}"
    return rng.choice(SPECIAL_NUMBERS)


def vector(rng: random.Random, low=-0.5, high=0.5) -> str:
    return " ".join(number(rng, low, high) for _ in range(3))


# --- elements ----------------------------------------------------------------------------------


def geometry(rng: random.Random, mesh_names: list[str]) -> tuple[str, float]:
    """A ``<geometry>`` and the volume of its shape (m³, 0 when unknown)."""
    kind = rng.choice(["box", "box", "cylinder", "sphere", "mesh", "mesh", "capsule", "odd"])
    if kind == "mesh" and not mesh_names:
        kind = "box"
    if kind == "box":
        size = [rng.uniform(0.02, 0.6) for _ in range(3)]
        return (
            f'<geometry><box size="{" ".join(f"{s:.4g}" for s in size)}"/></geometry>',
            math.prod(size),
        )
    if kind in ("cylinder", "capsule"):
        r, length = rng.uniform(0.01, 0.3), rng.uniform(0.02, 0.8)
        shape = f'<{kind} radius="{r:.4g}" length="{length:.4g}"/>'
        return f"<geometry>{shape}</geometry>", math.pi * r * r * length
    if kind == "sphere":
        r = rng.uniform(0.01, 0.3)
        return f'<geometry><sphere radius="{r:.4g}"/></geometry>', 4 / 3 * math.pi * r**3
    if kind == "mesh":
        name = rng.choice(mesh_names)
        scale = rng.choice(
            [
                "",
                "",
                ' scale="0.001 0.001 0.001"',
                ' scale="1 1 1"',
                f' scale="{vector(rng, 0.1, 2)}"',
            ]
        )
        return f'<geometry><mesh filename="{name}"{scale}/></geometry>', 0.0
    return rng.choice(
        ["<geometry/>", "<geometry><foo/></geometry>", '<geometry><box size="0 0 0"/></geometry>']
    ), 0.0


def origin(rng: random.Random) -> str:
    roll = rng.random()
    if roll < 0.4:
        return ""
    if roll < 0.7:
        return f'<origin xyz="{vector(rng)}"/>'
    rpy = rng.choice(["0 0 0", "1.5708 0 0", "0 1.5708 0", vector(rng, -3.2, 3.2)])
    return f'<origin xyz="{vector(rng)}" rpy="{rpy}"/>'


def inertial(rng: random.Random, volume: float) -> str:
    """An ``<inertial>``: right for its geometry, slipped, a placeholder, or broken."""
    mass = max(volume, 1e-4) * rng.choice([1000, 2700, 7850, 1, 1e6])
    kind = rng.choice(
        ["right", "right", "placeholder", "tiny", "broken", "about-origin", "incomplete"]
    )
    m = f"{mass:.6g}"
    i = max(volume, 1e-6) ** (2 / 3) * mass / 6
    if kind == "placeholder":
        moments = ("1", "0", "0", "1", "0", "1")
    elif kind == "tiny":
        moments = ("1e-12", "0", "0", "1e-12", "0", "1e-300")
    elif kind == "broken":
        moments = tuple(rng.choice(SPECIAL_NUMBERS) for _ in range(6))
        m = rng.choice(SPECIAL_NUMBERS)
    elif kind == "about-origin":
        moments = (f"{i + mass * 0.04:.6g}", "0", "0", f"{i + mass * 0.04:.6g}", "0", f"{i:.6g}")
    else:
        moments = (f"{i:.6g}", "0", "0", f"{i * 1.1:.6g}", "0", f"{i * 0.9:.6g}")
    names = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
    attributes = [f'{n}="{v}"' for n, v in zip(names, moments, strict=False)]
    if kind == "incomplete":
        del attributes[rng.randrange(6)]
    if rng.random() < 0.1:
        rng.shuffle(attributes)
    com = rng.choice(
        ["", f'<origin xyz="{vector(rng, -0.1, 0.1)}"/>', '<origin xyz="0 0 0.2" rpy="0 0 0"/>']
    )
    return f'<inertial>{com}<mass value="{m}"/><inertia {" ".join(attributes)}/></inertial>'


def link(rng: random.Random, name: str, mesh_names: list[str]) -> tuple[str, list[str], str]:
    parts = []
    shape, volume = geometry(rng, mesh_names)
    shape_origin = origin(rng)
    roll = rng.random()
    if roll < 0.7:
        parts.append(inertial(rng, volume))
    elif roll < 0.75:
        parts.append("<inertial/>")
    if rng.random() < 0.8:
        parts.append(f"<visual>{shape_origin}{shape}</visual>")
    if rng.random() < 0.75:
        parts.append(f"<collision>{shape_origin}{shape}</collision>")
    if rng.random() < 0.05:
        parts.append(f"<collision>{geometry(rng, mesh_names)[0]}</collision>")
    return f'<link name="{name}">', parts, "</link>"


def joint(rng: random.Random, index: int, parent: str, child: str) -> tuple[str, list[str], str]:
    kind = rng.choices((*JOINT_TYPES, "bogus"), weights=(30, 40, 10, 8, 3, 2, 1))[0]
    parts = [f'<parent link="{parent}"/>', f'<child link="{child}"/>', origin(rng)]
    if kind in ("revolute", "continuous", "prismatic") or rng.random() < 0.1:
        axis = rng.choice(["0 0 1", "1 0 0", "0 1 0", "0 0 0", "1 1 0", vector(rng)])
        parts.append(f'<axis xyz="{axis}"/>')
    if kind in ("revolute", "prismatic") and rng.random() < 0.9:
        parts.append(
            f'<limit lower="{number(rng, -3, 0)}" upper="{number(rng, 0, 3)}" '
            f'effort="{number(rng, 0, 100)}" velocity="{number(rng, 0, 10)}"/>'
        )
    return f'<joint name="j{index}" type="{kind}">', parts, "</joint>"


def layout(rng: random.Random, count: int) -> list[int]:
    """Each link's parent index (-1 for the root): a chain, a star or a random tree."""
    shape = rng.choice(["chain", "chain", "star", "tree"])
    if shape == "chain":
        return [i - 1 for i in range(count)]
    if shape == "star":
        return [-1] + [0] * (count - 1)
    return [-1] + [rng.randrange(i) for i in range(1, count)]


class Style:
    """How a file is written: indentation, newline, quotes, one element a line or all on one."""

    def __init__(self, rng: random.Random):
        self.indent = rng.choice(["  ", "  ", "    ", "\t", " "])
        self.nl = "\n"
        self.minified = rng.random() < 0.05
        self.nested = rng.random() < 0.7  # children on lines of their own

    def element(self, depth: int, head: str, parts: list[str], tail: str) -> str:
        parts = [p for p in parts if p]
        if self.minified:
            return head + "".join(parts) + tail
        pad = self.indent * depth
        if not self.nested or not parts:
            return pad + head + "".join(parts) + tail
        inner = "".join(f"{self.nl}{pad}{self.indent}{p}" for p in parts)
        return f"{pad}{head}{inner}{self.nl}{pad}{tail}"

    def join(self, lines: list[str]) -> str:
        return ("" if self.minified else self.nl).join(lines)


def urdf(rng: random.Random, count: int | None = None, mesh_names: list[str] | None = None) -> str:
    """A URDF robot of ``count`` links (drawn when None) with its joints."""
    count = count if count is not None else rng.choice([1, 2, 3, 3, 4, 5, 6, 8, 12, 20])
    style = Style(rng)
    names = [
        rng.choice(["base_link", "base", "world"]) if i == 0 else f"link_{i}" for i in range(count)
    ]
    parents = layout(rng, count)
    elements = [style.element(1, *link(rng, name, mesh_names or [])) for name in names]
    for i, parent in enumerate(parents):
        if parent >= 0:
            elements.append(style.element(1, *joint(rng, i, names[parent], names[i])))
    if rng.random() < 0.1:
        elements.insert(
            0,
            style.element(
                1, '<material name="grey">', ['<color rgba="0.5 0.5 0.5 1"/>'], "</material>"
            ),
        )
    if rng.random() < 0.1:
        elements.append(
            style.element(
                1, '<gazebo reference="base_link">', ["<static>true</static>"], "</gazebo>"
            )
        )
    if rng.random() < 0.1:
        where = rng.randrange(len(elements) + 1)
        elements.insert(
            where,
            f"{style.indent}<!-- inertia-lint: ignore[{rng.choice(SUPPRESSED)}] -->",
        )
    head = rng.choice(['<?xml version="1.0"?>', '<?xml version="1.0" encoding="UTF-8"?>', ""])
    lines = [head] if head else []
    lines += [f'<robot name="{rng.choice(["r", "fuzz_bot", "robot"])}">', *elements, "</robot>"]
    return style.join(lines) + style.nl


# --- xacro ---------------------------------------------------------------------------------------

PACKAGE = "fuzz_description"


def xacro_project(rng: random.Random, tree: Tree, folder: str = "") -> str:
    """
    A xacro robot in ``tree`` (under ``folder``): its main file, fragments it includes, a YAML
    file of parameters, a package.xml for ``$(find)``, and meshes. Returns the main file's path.
    """
    base = f"{folder}/" if folder else ""
    mesh_names = meshes.add_meshes(rng, tree, f"{base}meshes", count=rng.choice([0, 1, 2]))
    uris = [f"package://{PACKAGE}/meshes/{n}" for n in mesh_names] + [
        f"../meshes/{n}" for n in mesh_names
    ]
    tree.put(f"{base}package.xml", f"<package><name>{PACKAGE}</name></package>\n")
    tree.put(f"{base}config/params.yaml", "mass: 1.5\nsize: [0.1, 0.2, 0.3]\nname: arm\n")
    count = rng.choice([1, 2, 3, 4, 6])
    style = Style(rng)
    style.minified = False
    lines = [
        '<?xml version="1.0"?>',
        f'<robot name="fuzz" {XACRO_NS}>',
        '  <xacro:arg name="prefix" default=""/>',
        '  <xacro:arg name="use_mesh" default="true"/>',
        '  <xacro:property name="density" value="1000"/>',
        '  <xacro:property name="pi2" value="${pi/2}"/>',
    ]
    features = set(
        rng.sample(
            ["include", "find", "yaml", "env", "optenv", "if", "element", "block"],
            k=rng.randint(1, 5),
        )
    )
    if "include" in features:
        tree.put(f"{base}urdf/parts.xacro", fragment(rng, uris))
        lines.append('  <xacro:include filename="parts.xacro"/>')
    if "find" in features:
        tree.put(f"{base}urdf/more.xacro", fragment(rng, uris, macro="more_part"))
        lines.append(f'  <xacro:include filename="$(find {PACKAGE})/urdf/more.xacro"/>')
    if "yaml" in features:
        lines.append(
            '  <xacro:property name="params" '
            f"value=\"${{xacro.load_yaml('$(find {PACKAGE})/config/params.yaml')}}\"/>"
        )
    lines.append(
        '  <xacro:macro name="box_link" params="name mass:=1 size:=0.1 *origin">\n'
        '    <link name="${name}">\n'
        '      <inertial><xacro:insert_block name="origin"/><mass value="${mass}"/>\n'
        '        <inertia ixx="${mass*size*size/6}" ixy="0" ixz="0" iyy="${mass*size*size/6}"'
        ' iyz="0" izz="${mass*size*size/6}"/>\n'
        "      </inertial>\n"
        '      <collision><geometry><box size="${size} ${size} ${size}"/></geometry></collision>\n'
        "    </link>\n"
        "  </xacro:macro>"
    )
    names = ["$(arg prefix)base"]
    lines.append('  <link name="$(arg prefix)base"/>')
    for i in range(1, count + 1):
        name = f"$(arg prefix)l{i}"
        names.append(name)
        mass = rng.choice(
            [
                "1",
                "${density*0.001}",
                "2.5",
                "${params['mass']}" if "yaml" in features else "0.5",
                number(rng),
            ]
        )
        size = rng.choice(["0.1", "${0.05*2}", number(rng, 0.01, 0.5)])
        call = rng.choice(
            [
                "box_link",
                "box_link",
                "part" if "include" in features else "box_link",
                "more_part" if "find" in features else "box_link",
            ]
        )
        if call == "box_link":
            lines.append(
                f'  <xacro:box_link name="{name}" mass="{mass}" size="{size}">'
                f'<origin xyz="0 0 ${{{size}/2}}"/></xacro:box_link>'
            )
        else:
            lines.append(f'  <xacro:{call} name="{name}" mass="{mass}"/>')
        kind = rng.choice(["revolute", "continuous", "fixed", "prismatic"])
        lines.append(
            f'  <joint name="j{i}" type="{kind}"><parent link="{names[i - 1]}"/>'
            f'<child link="{name}"/>'
            f'<origin xyz="0 0 0.1" rpy="0 0 ${{pi2}}"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="10" velocity="1"/></joint>'
        )
    if "env" in features:
        lines.append(f'  <link name="env_$(env {SECRET_VAR})"/>')
        lines.append(
            f'  <joint name="jenv" type="fixed"><parent link="{names[0]}"/>'
            f'<child link="env_$(env {SECRET_VAR})"/></joint>'
        )
        tree.env[SECRET_VAR] = SECRET
    if "optenv" in features:
        lines.append(f'  <xacro:property name="from_env" value="$(optenv {SECRET_VAR} 0.25)"/>')
        lines.append(
            '  <xacro:box_link name="optenv_${from_env}" size="0.1" mass="1">'
            '<origin xyz="0 0 0"/></xacro:box_link>'
        )
        lines.append(
            f'  <joint name="jopt" type="revolute"><parent link="{names[0]}"/>'
            '<child link="optenv_${from_env}"/><axis xyz="0 0 1"/>'
            '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        )
        if rng.random() < 0.5:
            tree.env[SECRET_VAR] = SECRET
    if "if" in features:
        lines.append(
            '  <xacro:if value="$(arg use_mesh)"><link name="if_link"><visual><geometry>'
            '<sphere radius="0.05"/></geometry></visual></link></xacro:if>'
        )
        lines.append(
            '  <xacro:unless value="${density > 10}"><link name="unless_link"/></xacro:unless>'
        )
    if "element" in features:
        lines.append(
            '  <xacro:element xacro:name="link" name="element_link">'
            '<xacro:attribute name="type" value="x"/></xacro:element>'
        )
    if "block" in features:
        lines.append(
            '  <xacro:macro name="wrap" params="**body"><xacro:insert_block name="body"/>'
            "</xacro:macro>"
            '<xacro:wrap><body><link name="wrapped"/></body></xacro:wrap>'
        )
    lines += ["</robot>", ""]
    main = f"{base}urdf/robot.urdf.xacro"
    tree.put(main, "\n".join(lines))
    return main


def fragment(rng: random.Random, uris: list[str], macro: str = "part") -> str:
    """A fragment of macros that a robot includes."""
    shape = (
        f'<mesh filename="{rng.choice(uris)}"/>'
        if uris and rng.random() < 0.6
        else '<cylinder radius="0.05" length="0.2"/>'
    )
    return (
        f'<?xml version="1.0"?>\n<robot {XACRO_NS}>\n'
        f'  <xacro:macro name="{macro}" params="name mass:=1">\n'
        '    <link name="${name}">\n'
        '      <inertial><mass value="${mass}"/>\n'
        '        <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>\n'
        f"      <visual><geometry>{shape}</geometry></visual>\n"
        f"      <collision><geometry>{shape}</geometry></collision>\n"
        "    </link>\n"
        "  </xacro:macro>\n"
        "</robot>\n"
    )


def urdf_input(rng: random.Random, tree: Tree, count: int | None = None) -> str:
    """A URDF robot with its meshes beside it in ``tree``; its path."""
    mesh_names = meshes.add_meshes(rng, tree, "meshes", count=rng.choice([0, 0, 1, 2, 3]))
    uris = [f"../meshes/{n}" for n in mesh_names]
    if mesh_names and rng.random() < 0.5:
        tree.put("package.xml", f"<package><name>{PACKAGE}</name></package>\n")
        uris = [f"package://{PACKAGE}/meshes/{n}" for n in mesh_names]
    if rng.random() < 0.1:
        uris += ["missing.stl", "package://nopkg/x.stl", "file:///nonexistent/x.stl"]
    main = rng.choice(["urdf/robot.urdf", "urdf/robot.urdf", "urdf/robot.xacro", "robot.urdf"])
    if main == "robot.urdf":
        uris = [u.replace("../meshes", "meshes") for u in uris]
    tree.put(main, urdf(rng, count, uris))
    return main
