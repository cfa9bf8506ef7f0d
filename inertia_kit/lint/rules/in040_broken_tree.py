"""IN040 broken-tree: the links and joints do not form one tree."""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterator

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.description import model
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.options import Option
from inertia_kit.lint.rules import RuleContext

CODE = "IN040"
NAME = "broken-tree"
SEVERITY = Severity.ERROR
SCOPE = "robot"
# URDF's joints name their links; MJCF nests its bodies
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "duplicate names, joints naming unknown links, several roots, cycles, a link with two "
    "parents, a joint without parent/child or of an unknown type"
)
OPTIONS = (Option("extra_joint_types", tuple, (), "joint types to accept besides URDF's six"),)

SHOWN = 3  # joints of a cycle the message names; the rest are counted (the detail has the cycle)
JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
# joint types one engine reads in URDF and urdfdom (so ROS, Gazebo) rejects
EXTENSIONS = {
    "spherical": "PyBullet's ball joint",
    "ball": "Drake's ball joint",
    "universal": "Drake's universal joint",
    "screw": "Drake's screw joint",
}


def _line(source: model.Source) -> str:
    site = source.calls[-1] if source.calls else source
    return f"line {site.line}" if site.line is not None else site.path


def _guess(name: str, options: list[str]) -> str:
    import difflib  # a broken tree only: not imported by every run

    close = difflib.get_close_matches(name, options, n=1, cutoff=0.6)
    return f" (did you mean `{close[0]}`?)" if close else ""


def check(robot: RobotAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    urdf = robot.robot
    yield from _names(urdf, ctx)
    links = {link.name for link in urdf.links if link.name}
    yield from _joints(urdf, links, ctx, tuple(ctx.option("extra_joint_types")))
    yield from _parents(urdf, links, ctx)
    yield from _roots(urdf, links, ctx)
    yield from _cycles(urdf, links, ctx)


def _names(urdf: model.Robot, ctx: RuleContext) -> Iterator[Finding]:
    # a xacro file without links or joints never gets here: it loads as a fragment
    if not urdf.links:
        yield ctx.finding(
            "the robot has no <link>",
            urdf.source,
            detail='urdfdom refuses it ("No link elements found in urdf file")',
            help="a robot description needs at least one link",
        )
    for kind, elements in (("link", urdf.links), ("joint", urdf.joints)):
        first: dict[str, model.Link | model.Joint] = {}
        for element in elements:
            if not element.name:
                yield ctx.finding(
                    f"a <{kind}> has no name: urdfdom refuses the file",
                    element.source,
                    help=f"give the {kind} a unique name",
                    **{kind: None},
                )
                continue
            if element.name in first:
                yield ctx.finding(
                    f"{kind} `{element.name}` is defined twice (first at "
                    f"{_line(first[element.name].source)})",
                    element.source,
                    detail="urdfdom refuses the file, others keep one of the two",
                    help=f"rename or remove one of the two {kind}s",
                    **{kind: element.name},
                )
            else:
                first[element.name] = element


def _joints(
    urdf: model.Robot, links: set[str], ctx: RuleContext, extra: tuple[str, ...]
) -> Iterator[Finding]:
    names = sorted(links)
    for joint in urdf.joints:
        name = joint.name or None
        label = f"joint `{joint.name}`" if joint.name else "a joint"
        if joint.type not in JOINT_TYPES and joint.type not in extra:
            if joint.type in EXTENSIONS:
                what = f"type `{joint.type}` ({EXTENSIONS[joint.type]}, no URDF type)"
            elif joint.type:
                what = f"unknown type `{joint.type}`{_guess(joint.type, list(JOINT_TYPES))}"
            else:
                what = "no type"
            yield ctx.finding(
                f"{label} has {what}",
                joint.source,
                detail=f'urdfdom refuses the file ("Joint [{joint.name}] has no known type '
                f'[{joint.type}]"), and with it ROS and Gazebo',
                joint=name,
                help=f"use one of {', '.join(JOINT_TYPES)}; if the file is only for an engine "
                "that reads this type, list it in the rule's extra_joint_types",
            )
        for role, link in (("parent", joint.parent), ("child", joint.child)):
            if not link:
                yield ctx.finding(
                    f"{label} has no <{role} link>: urdfdom refuses the file",
                    joint.source,
                    joint=name,
                    help=f'add <{role} link="..."/> naming an existing link',
                )
            elif link not in links:
                yield ctx.finding(
                    f"{label} names {role} link `{link}`, which does not exist"
                    f"{_guess(link, names)}",
                    joint.source,
                    joint=name,
                    help="name an existing link, or add the missing link",
                )
        if joint.parent and joint.parent == joint.child:
            yield ctx.finding(
                f"{label} joins link `{joint.parent}` to itself",
                joint.source,
                joint=name,
                help="a joint connects a parent link to a different child link",
            )


def _parents(urdf: model.Robot, links: set[str], ctx: RuleContext) -> Iterator[Finding]:
    first: dict[str, model.Joint] = {}
    for joint in urdf.joints:
        child = joint.child
        if not child or child not in links or child == joint.parent:
            continue
        if child in first:
            other = first[child]
            yield ctx.finding(
                f"link `{child}` has two parent joints: `{other.name}` ({_line(other.source)}) "
                f"and `{joint.name}`",
                joint.source,
                detail="a URDF is a tree, a closed chain cannot be written in it; urdfdom "
                "refuses the file",
                joint=joint.name or None,
                link=child,
                help="keep one parent joint; model a closed chain with a mimic joint or the "
                "simulator's own loop constraint (SDFormat, MJCF equality)",
            )
        else:
            first[child] = joint


def _parent_map(urdf: model.Robot, links: set[str]) -> dict[str, model.Joint]:
    """child link -> its first joint from a known parent link."""
    parents: dict[str, model.Joint] = {}
    for joint in urdf.joints:
        if joint.child in links and joint.parent in links and joint.child != joint.parent:
            parents.setdefault(joint.child, joint)  # type: ignore[arg-type]
    return parents


def _roots(urdf: model.Robot, links: set[str], ctx: RuleContext) -> Iterator[Finding]:
    children = {joint.child for joint in urdf.joints if joint.child}
    seen: set[str] = set()
    roots = []
    for link in urdf.links:
        if link.name and link.name not in children and link.name not in seen:
            roots.append(link)
        seen.add(link.name)
    if not roots:
        if links:
            yield ctx.finding(
                "no root link: the joints form a cycle",
                urdf.source,
                detail='every link is some joint\'s child (urdfdom: "No root link found")',
                help="the link the robot is built from (base_link) must be no joint's child",
            )
        return
    if len(roots) == 1:
        return
    parents = _parent_map(urdf, links)
    below = Counter()
    for link in links:
        current, visited = link, set()
        while current in parents and current not in visited:
            visited.add(current)
            current = parents[current].parent  # type: ignore[assignment]
        below[current] += 1
    main = max(roots, key=lambda link: below[link.name])  # first of the largest on a tie
    for link in roots:
        if link is main:
            continue
        size = below[link.name]
        what = "a link" if size <= 1 else f"a subtree of {size} links"
        yield ctx.finding(
            f"link `{link.name}` is a second root ({what} no joint connects to the tree of "
            f"`{main.name}`)",
            link.source,
            detail="urdfdom refuses several roots, Gazebo and PyBullet load one body per root "
            "or fail",
            link=link.name,
            help=f"connect `{link.name}` with a joint (fixed, if it does not move) to a link "
            f"of `{main.name}`'s tree, or remove it",
        )


def _cycles(urdf: model.Robot, links: set[str], ctx: RuleContext) -> Iterator[Finding]:
    parents = _parent_map(urdf, links)
    done: set[str] = set()
    for start in (link.name for link in urdf.links):
        path: list[str] = []
        on_path: set[str] = set()
        current = start
        while current in parents and current not in done and current not in on_path:
            path.append(current)
            on_path.add(current)
            current = parents[current].parent  # type: ignore[assignment]
        if current in on_path:
            cycle = path[path.index(current) :]
            joints = [parents[link] for link in cycle]
            # report at the last joint of the cycle in the file: the one that closed it
            closing = max(joints, key=lambda j: urdf.joints.index(j))
            chain = " → ".join(f"`{link}`" for link in [*reversed(cycle), cycle[-1]])
            names = [f"`{j.name}`" for j in joints]
            if len(names) > SHOWN:
                names = [*names[:SHOWN], f"{len(names) - SHOWN} more"]
            yield ctx.finding(
                f"joints {', '.join(names[:-1])} and {names[-1]} form a cycle",
                closing.source,
                detail=f"the cycle: {chain}",
                joint=closing.name or None,
                help="a URDF is a tree: remove or re-parent one joint of the cycle",
            )
        done.update(path)
