"""
Seed inputs: the example robots (examples/, each package whole, one robot file given), robots
the test kit builds (kit.urdf, kit.xacro_projects, kit.runaway_xacro), and the synthetic
generators (fuzz.robots), with configuration files beside them (fuzz.configs).
"""

from __future__ import annotations

import functools
import random
from pathlib import Path

from kit import EXAMPLES
from kit import urdf as k
from kit.runaway_xacro import HUGE_STRING, doubling_chain, expression_robot
from kit.xacro_projects import LEAF, PACKAGE, middle
from kit.xacro_projects import robot as project_robot

from fuzz import configs, robots
from fuzz.tree import Tree, file

ROBOT_SUFFIXES = (".urdf", ".xacro")


@functools.cache
def example_packages() -> dict[str, dict[str, bytes]]:
    """package name -> {path inside the package: bytes}, every file of examples/."""
    packages: dict[str, dict[str, bytes]] = {}
    for package in sorted(p for p in EXAMPLES.iterdir() if p.is_dir()):
        files = {}
        for path in sorted(package.rglob("*")):
            if path.is_file() and path.suffix != ".py" and "__pycache__" not in path.parts:
                files[str(path.relative_to(package))] = path.read_bytes()
        packages[package.name] = files
    return packages


def example(rng: random.Random, tree: Tree) -> str:
    """One example package (sometimes two), one of its robot files the main one."""
    packages = example_packages()
    chosen = rng.sample(sorted(packages), k=rng.choice([1, 1, 1, 2]))
    robots_found = []
    for name in chosen:
        for path, data in packages[name].items():
            tree.put(f"{name}/{path}", data)
            if Path(path).suffix in ROBOT_SUFFIXES:
                robots_found.append(f"{name}/{path}")
    tree.notes.append(f"example {'+'.join(chosen)}")
    return rng.choice(robots_found)


def kit_robot(rng: random.Random, tree: Tree) -> str:
    """A robot the test kit's builders write."""
    choice = rng.choice(["moving", "lines", "project", "runaway", "builders"])
    tree.notes.append(f"kit {choice}")
    if choice == "moving":
        body = k.link(
            "arm",
            k.inertial(rng.choice([1, 0, -1, "nan"]), rng.choice([0.01, 1, 1e-12])),
            k.collision(k.box(0.1, 0.2, 0.3)),
        )
        tree.put(
            "robot.urdf",
            k.moving(body, kind=rng.choice(["revolute", "fixed", "floating", "continuous"])),
        )
        return "robot.urdf"
    if choice == "lines":
        parts = [
            k.link_lines("base"),
            k.joint_lines("base", "arm"),
            k.link_lines("arm", mass=rng.choice([2, 0, None]), moment=rng.choice([0.01, 1, None])),
        ]
        tree.put("robot.urdf", k.robot_lines(*parts, head='<?xml version="1.0"?>\n'))
        return "robot.urdf"
    if choice == "project":
        tree.put(".git/HEAD", "ref: refs/heads/main\n")
        tree.put(f"{PACKAGE}/package.xml", f"<package><name>{PACKAGE}</name></package>\n")
        tree.put(f"{PACKAGE}/urdf/leaf.xacro", LEAF)
        tree.put(f"{PACKAGE}/urdf/middle.xacro", middle("leaf.xacro"))
        include = rng.choice(
            ["leaf.xacro", "middle.xacro", f"$(find {PACKAGE})/urdf/leaf.xacro", "missing.xacro"]
        )
        calls = [
            f"a{i}={rng.choice(['1', '0', '-2', '${1/0}', 'nan', '2.5'])}"
            for i in range(rng.randint(1, 3))
        ]
        tree.put(f"{PACKAGE}/urdf/arm.urdf.xacro", project_robot(include, *calls))
        if rng.random() < 0.5:
            tree.put(
                f"{PACKAGE}/urdf/arm2.urdf.xacro",
                project_robot("middle.xacro", "b1=3", name="arm2"),
            )
        return rng.choice(
            [
                f"{PACKAGE}/urdf/arm.urdf.xacro",
                f"{PACKAGE}/urdf/leaf.xacro",
                f"{PACKAGE}/urdf/middle.xacro",
            ]
        )
    if choice == "runaway":
        text = rng.choice(
            [
                expression_robot(
                    rng.choice(
                        [
                            "'x'*10**4",
                            "'x'*10**6",
                            HUGE_STRING.replace("10**10", "10**8"),
                            "1+1",
                            "[0]*10**7",
                        ]
                    )
                ),
                doubling_chain(rng.choice([3, 8, 12, 17])),
            ]
        )
        tree.put("runaway.xacro", text)
        return "runaway.xacro"
    link_count = rng.choice([1, 2, 5])
    parts = [k.link("base")]
    for i in range(link_count):
        parts += [
            k.joint(
                "base" if i == 0 else f"l{i - 1}",
                f"l{i}",
                rng.choice(["revolute", "fixed", "prismatic"]),
                name=f"j{i}",
            ),
            k.link(
                f"l{i}",
                k.box_inertial(rng.uniform(0.1, 5), (0.1, 0.2, 0.3)),
                k.collision(k.box(0.1, 0.2, 0.3)),
                k.visual(k.cylinder(0.05, 0.2)),
            ),
        ]
    tree.put("robot.urdf", k.robot(*parts, sep=rng.choice(["", "\n", "\n  "])))
    return "robot.urdf"


def big_robot(rng: random.Random, tree: Tree, links: int) -> str:
    """A URDF of ``links`` links (chain, star or tree): the linear-time cases."""
    tree.notes.append(f"big {links} links")
    tree.put("big.urdf", robots.urdf(rng, links, []))
    return "big.urdf"


#: source -> weight
SOURCES = {"urdf": 30, "xacro": 20, "example": 20, "kit": 15, "big": 3}


def seed(rng: random.Random, big_links: tuple[int, ...]) -> Tree:
    """A fresh input: a robot from one of the sources, with configuration files beside it."""
    tree = Tree()
    source = rng.choices(list(SOURCES), weights=list(SOURCES.values()))[0]
    if source == "urdf":
        tree.notes.append("urdf")
        main = robots.urdf_input(rng, tree)
    elif source == "xacro":
        tree.notes.append("xacro")
        main = robots.xacro_project(rng, tree, rng.choice(["", "fuzz_description"]))
    elif source == "example":
        main = example(rng, tree)
    elif source == "kit":
        main = kit_robot(rng, tree)
    else:
        main = big_robot(rng, tree, rng.choice(big_links))
    configs.add_configs(rng, tree)
    tree.main = main
    if rng.random() < 0.1:
        tree.main = "."  # the whole folder, walked
    return tree


__all__ = ["example", "file", "kit_robot", "seed"]
