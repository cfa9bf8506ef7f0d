"""
File-system layouts a hostile repository can hold: symbolic links in and out of it, loops of
links, FIFOs, links to /dev/zero, unreadable files and folders, missing meshes, huge (sparse)
files, deep folders, control characters in file names, and links planted where a command
writes its output (``-o``). ``outside/`` holds what the links out point at: a script with its
execute bit, a robot, a mesh; no command may change them.
"""

from __future__ import annotations

import random
from pathlib import PurePosixPath

from fuzz.tree import OUTSIDE, Node, Tree, file, link

#: what outside/ holds in every input
DEPLOY = b"#!/bin/sh\necho deploying\n"
OUTSIDE_ROBOT = (
    b'<?xml version="1.0"?>\n<robot name="outside">\n  <link name="base"/>\n'
    b'  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>'
    b'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>\n'
    b'  <link name="arm"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    b"</link>\n</robot>\n"
)

#: the outputs commands write with -o (fuzz.plan), where a link may be planted
OUTPUT_NAMES = ("report.out", "filled.urdf", "review.html")

HUGE = 3 << 30  # a sparse 3 GB file


def add_outside(tree: Tree) -> None:
    tree.nodes[f"{OUTSIDE}/deploy.sh"] = file(DEPLOY, 0o755)
    tree.nodes[f"{OUTSIDE}/robot.urdf"] = file(OUTSIDE_ROBOT, 0o644)
    tree.nodes[f"{OUTSIDE}/secret.txt"] = file(b"outside secret\n", 0o600)


def _pick(rng: random.Random, tree: Tree, suffixes: tuple[str, ...]) -> str | None:
    found = [p for p in tree.work_files() if PurePosixPath(p).suffix.lower() in suffixes]
    return rng.choice(found) if found else None


def _up(path: str) -> str:
    """The relative way from ``path``'s folder (below work/) to the run's root."""
    return "../" * (len(PurePosixPath(path).parts))


def layout(rng: random.Random, tree: Tree) -> str | None:
    op = rng.choice(LAYOUTS)
    return op(rng, tree)


def robot_link_in(rng, tree):
    if tree.main == "." or tree.get(tree.main) is None:
        return None
    real = str(PurePosixPath(tree.main).parent / ("real_" + PurePosixPath(tree.main).name))
    tree.put(real, tree.get(tree.main))
    tree.put(tree.main, link(PurePosixPath(real).name))
    return f"layout robot link in {tree.main} -> {real}"


def robot_link_out(rng, tree):
    if tree.main == ".":
        return None
    tree.put(tree.main, link(_up(tree.main) + "outside/robot.urdf"))
    return f"layout robot link out {tree.main}"


def mesh_change(rng, tree):
    mesh = _pick(rng, tree, (".stl", ".obj", ".dae", ".ply", ".glb"))
    if mesh is None:
        return None
    how = rng.choice(
        ["missing", "fifo", "zero", "unreadable", "huge", "folder", "out", "loop", "dangling"]
    )
    if how == "missing":
        del tree.nodes[tree.key(mesh)]
    elif how == "fifo":
        tree.put(mesh, Node("fifo"))
    elif how == "zero":
        tree.put(mesh, link("/dev/zero"))
    elif how == "unreadable":
        tree.put(mesh, Node("file", tree.get(mesh).data, mode=0))
    elif how == "huge":
        tree.put(mesh, Node("sparse", tree.get(mesh).data[:84], size=HUGE))
    elif how == "folder":
        del tree.nodes[tree.key(mesh)]
        tree.put(mesh, Node("dir"))
    elif how == "out":
        tree.nodes[f"{OUTSIDE}/mesh.stl"] = tree.get(mesh)
        tree.put(mesh, link(_up(mesh) + "outside/mesh.stl"))
    elif how == "loop":
        tree.put(mesh, link(PurePosixPath(mesh).name))
    else:
        tree.put(mesh, link("nowhere.stl"))
    return f"layout mesh {how} {mesh}"


def config_change(rng, tree):
    name = rng.choice(
        [".gitignore", ".gitignore", "pyproject.toml", ".inertia-kit.toml", ".git/info/exclude"]
    )
    how = rng.choice(["zero", "fifo", "huge", "unreadable", "folder", "loop", "huge-line"])
    if how == "zero":
        node = link("/dev/zero")
    elif how == "fifo":
        node = Node("fifo")
    elif how == "huge":
        node = Node("sparse", b"*.stl\n", size=HUGE)
    elif how == "unreadable":
        node = Node(
            "file", b"[tool.inertia-kit]\n" if name.endswith("toml") else b"*.stl\n", mode=0
        )
    elif how == "folder":
        node = Node("dir")
    elif how == "loop":
        node = link(PurePosixPath(name).name)
    else:
        node = file(b"a" * (8 << 20) + b"\n")
    tree.nodes.pop(tree.key(name), None)
    tree.put(name, node)
    return f"layout config {how} {name}"


def loops(rng, tree):
    how = rng.choice(["self", "parent", "pair", "package"])
    if how == "self":
        tree.put("loop", link("."))
    elif how == "parent":
        tree.put("sub/up", link(".."))
    elif how == "pair":
        tree.put("a.urdf", link("b.urdf"))
        tree.put("b.urdf", link("a.urdf"))
    else:  # a package:// mesh of a package nobody has, and a loop where packages are looked for
        tree.put("pkgs/loop", link("."))
        tree.put("pkgs/deeper/again", link("../.."))
        robot = tree.get(tree.main) if tree.main != "." else None
        if robot is not None and robot.kind == "file":
            data = robot.data.replace(
                b"</robot>",
                b'<link name="ghost_mesh"><visual><geometry><mesh filename="package://unknown_pkg/m.stl"/></geometry></visual></link></robot>',
                1,
            )
            tree.put(tree.main, file(data))
    return f"layout loop {how}"


def deep_folders(rng, tree):
    depth = rng.choice([50, 200, 600, 1100])
    folder = "/".join(["d"] * depth)  # short names: 1100 deep is 2200 characters
    tree.put(f"{folder}/deep.urdf", b'<robot name="deep"><link name="a"/></robot>\n')
    return f"layout deep folders {depth}"


def unreadable_folder(rng, tree):
    files = tree.work_files()
    folders = sorted({str(PurePosixPath(p).parent) for p in files} - {"."})
    if not folders:
        return None
    folder = rng.choice(folders)
    tree.put(folder, Node("dir", mode=rng.choice([0, 0o111, 0o444])))
    return f"layout unreadable folder {folder}"


def planted_output(rng, tree):
    """A link at each path a command writes with -o (fuzz.plan), pointing out of the tree."""
    target = rng.choice(["../outside/deploy.sh", "../outside/robot.urdf", "/dev/null", "nowhere/x"])
    for name in OUTPUT_NAMES:
        tree.put(name, link(target))
    return f"layout planted outputs -> {target}"


def control_names(rng, tree):
    if tree.main == "." or tree.get(tree.main) is None:
        return None
    path = PurePosixPath(tree.main)
    new = str(
        path.parent
        / (
            rng.choice(
                [
                    "ro\nFUZZINJ bot",
                    "ro\rbot",
                    "ro\x1b[31mbot",
                    "ro\u2028FUZZINJ",
                    "robot with spaces",
                    "röböt",
                    "-rf",
                    "ro\tbot",
                ]
            )
            + "".join(path.suffixes)
        )
    )
    tree.nodes[tree.key(new)] = tree.nodes.pop(tree.key(tree.main))
    tree.main = new
    return f"layout control characters in the robot's name {new!r}"


def many_files(rng, tree):
    count = rng.choice([50, 300])
    for i in range(count):
        tree.put(
            f"many/r{i}.urdf",
            f'<robot name="r{i}"><link name="a"/><link name="b"/><joint name="j" '
            'type="revolute"><parent link="a"/><child link="b"/></joint></robot>\n',
        )
    return f"layout many files {count}"


def unreadable_robot(rng, tree):
    if tree.main == "." or tree.get(tree.main) is None or tree.get(tree.main).kind != "file":
        return None
    tree.put(tree.main, Node("file", tree.get(tree.main).data, mode=rng.choice([0, 0o222, 0o444])))
    return f"layout robot mode {tree.main}"


LAYOUTS = (
    robot_link_in, robot_link_out, mesh_change, mesh_change, config_change, config_change,
    loops, deep_folders, unreadable_folder, planted_output, planted_output, control_names,
    many_files, unreadable_robot,
)  # fmt: skip
