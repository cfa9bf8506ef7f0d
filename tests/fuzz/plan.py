"""
What is run on one input: :class:`Invocation` s of ``inertia-lint``, ``inertia-fill`` and
``inertia-kit`` (report, mass, view, rules), with options drawn from a ``random.Random``. Each
input gets a lint in one of the output formats, a writing command (``--fix``, fill,
``--add-noqa``) and one other command; every command and format is covered across inputs, and
:func:`Invocation.coverage` names what each run covers so that a campaign can count them.
"""

from __future__ import annotations

import dataclasses
import random
from dataclasses import dataclass, field
from pathlib import PurePosixPath

from fuzz.mutate import SPECIALS, robot_files
from fuzz.tree import Tree
from inertia_kit.lint import catalog

PROGRAMS = ("inertia-lint", "inertia-fill", "inertia-kit")
LINT_FORMATS = ("full", "concise", "json", "github", "sarif", "junit", "gitlab")
#: how each format's stdout is checked: text (escaped lines), json, xml
FORMAT_KIND = {
    "full": "text",
    "concise": "text",
    "github": "text",
    "json": "json",
    "sarif": "json",
    "junit": "xml",
    "gitlab": "json",
}
FILL_MODES = ("missing", "invalid", "all")
MASS_SHAPES = {
    "box": (("--size", 3),),
    "cylinder": (("--radius", 1), ("--length", 1)),
    "sphere": (("--radius", 1),),
    "capsule": (("--radius", 1), ("--length", 1)),
    "ellipsoid": (("--radii", 3),),
}


@dataclass(frozen=True)
class Invocation:
    """
    One command line. ``program``: the console script (``inertia-lint``, ``inertia-fill``,
    ``inertia-kit``); ``stdin``: a path (relative to work/) fed to standard input; ``writes``:
    it may edit robot files in place; ``output``: the file it writes with ``-o`` (relative to
    work/) and ``output_kind`` how to read it; ``stdout_kind``: text, json, xml, diff or robot
    (a robot text: fill ``-``); ``real``: run the installed script in a process of its own
    instead of the command in a forked copy of the harness.
    """

    program: str
    args: tuple[str, ...]
    covers: tuple[str, ...]
    stdin: str | None = None
    writes: bool = False
    output: str | None = None
    output_kind: str | None = None
    stdout_kind: str = "text"
    real: bool = False

    def line(self) -> str:
        """The shell line that reruns it (in work/)."""
        import shlex

        command = " ".join(shlex.quote(a) for a in (self.program, *self.args))
        return f"{command} < {shlex.quote(self.stdin)}" if self.stdin else command

    def coverage(self) -> tuple[str, ...]:
        return (*self.covers, f"real {self.program}") if self.real else self.covers


@dataclass
class Plan:
    plain: list[Invocation] = field(default_factory=list)  # commands that write no robot file
    writers: list[Invocation] = field(
        default_factory=list
    )  # each run twice: the 2nd changes nothing
    interrupt: Invocation | None = None  # a writer that, if it edits, is run again and SIGKILLed
    concurrent: tuple[Invocation, Invocation] | None = None  # two writers at once


def _paths(tree: Tree) -> tuple[str, ...]:
    return (tree.main,)


def _file(tree: Tree) -> str | None:
    """A robot file for the commands that take one (report, view, mass)."""
    if tree.main != ".":
        return tree.main
    found = robot_files(tree)
    return found[0] if found else None


def _selection(rng: random.Random) -> list[str]:
    codes = [r.CODE for r in catalog.RULES]
    args: list[str] = []
    roll = rng.random()
    if roll < 0.15:
        args += [
            "--select",
            ",".join(rng.sample([*codes, "IN0", "IN01", "IN07"], rng.randint(1, 3))),
        ]
    elif roll < 0.2:
        args += ["--select", rng.choice(["IN999", "nonsense", "", "placeholder-inertia", "in0"])]
    if rng.random() < 0.1:
        args += ["--ignore", rng.choice(codes)]
    return args


def _common(rng: random.Random, tree: Tree) -> list[str]:
    args: list[str] = []
    if rng.random() < 0.15:
        args += ["--package-path", rng.choice([".", "pkgs", "nowhere"])]
    if rng.random() < 0.1:
        args += [
            "--xacro-arg",
            rng.choice(["prefix:=x_", "use_mesh:=false", "bogus", "prefix:=a\nFUZZINJ"]),
        ]
    return args


def config_fixes(tree: Tree) -> bool:
    """Whether a configuration file may turn on ``fix`` (then a plain lint writes)."""
    return any(k.endswith((".toml",)) and b"fix" in n.data for k, n in tree.nodes.items())


def lint(rng: random.Random, tree: Tree, fmt: str | None = None) -> Invocation:
    fmt = fmt or rng.choice(LINT_FORMATS)
    args = ["--output-format", fmt, *_selection(rng), *_common(rng, tree)]
    covers = [f"lint --output-format {fmt}"]
    if rng.random() < 0.3:
        args += ["--engine", "all"]
        covers.append("lint --engine all")
    elif rng.random() < 0.15:
        args += ["--engine", rng.choice(["mujoco", "drake", "gazebo,pybullet", "kdl", "bogus"])]
    if rng.random() < 0.1:
        args.append("--statistics")
        covers.append("lint --statistics")
    if rng.random() < 0.1:
        args += ["--fail-on", rng.choice(["error", "warning", "info"])]
    if rng.random() < 0.05:
        args.append("--exit-zero")
    if rng.random() < 0.1:
        args.append("-q")
    if rng.random() < 0.05:
        args.append(rng.choice(["--no-respect-gitignore", "--force-exclude", "--show-files"]))
    jobs = "2" if rng.random() < 0.03 else "1"
    if jobs == "2":
        covers.append("lint -j 2")
    args += ["-j", jobs]
    output, output_kind, stdout_kind = None, None, FORMAT_KIND[fmt]
    if "--statistics" in args or "--show-files" in args:
        stdout_kind = "text"
    planted = tree.get("report.out") is not None
    if rng.random() < (0.8 if planted else 0.15):
        output = "report.out"
        args += ["-o", output]
        output_kind, stdout_kind = stdout_kind, "text"
        covers.append("lint -o")
    writes = config_fixes(tree)
    if writes:
        args.append("--no-fix") if rng.random() < 0.5 else covers.append(
            "lint fix from the configuration"
        )
        writes = "--no-fix" not in args
    return Invocation(
        "inertia-lint",
        (*args, *_paths(tree)),
        tuple(covers),
        writes=writes,
        output=output,
        output_kind=output_kind,
        stdout_kind=stdout_kind,
    )


WRITER_KINDS = ("fill", "fix", "fill", "unsafe", "noqa")
OTHER_KINDS = (
    "diff", "fill-diff", "fill-check", "fill-o", "report", "lumped", "view", "mass", "mesh",
    "rules", "explain", "stdin-lint", "stdin-fill", "stdin-fix", "report",
)  # fmt: skip


def writer(rng: random.Random, tree: Tree, kind: str | None = None) -> Invocation:
    kind = kind or rng.choice(WRITER_KINDS)
    common = _common(rng, tree)
    if kind == "fill":
        mode = rng.choice(FILL_MODES)
        args = ["--fix", mode, *common]
        roll = rng.random()
        if roll < 0.2:
            args += [
                "--density",
                rng.choice(["1000", "2700.5", "0", "-1", "nan", "1e308", "5e-324"]),
            ]
        elif roll < 0.3:
            args += ["--material", rng.choice(["steel", "aluminium", "unobtainium", "PLA"])]
        elif roll < 0.4:
            args += [
                "--mass",
                rng.choice(["link_1", "l1", "arm", "base_link", "nope"])
                + "="
                + rng.choice(["1.5", "0", "-2", "nan", "1e308"]),
            ]
        elif roll < 0.45:
            args += ["--total-mass", rng.choice(["12.5", "0", "1e-300", "inf"])]
        elif roll < 0.5:
            args += ["--link", rng.choice(["link_1", "base_link", "nope"])]
        return Invocation(
            "inertia-fill",
            (*args, *_paths(tree)),
            (f"fill --fix {mode}",),
            writes=True,
            stdout_kind="text",
        )
    if kind == "noqa":
        return Invocation(
            "inertia-lint",
            ("--add-noqa", *_selection(rng), *common, *_paths(tree)),
            ("lint --add-noqa",),
            writes=True,
        )
    args = ["--fix", *common]
    covers = ["lint --fix"]
    if kind == "unsafe":
        args.append("--unsafe-fixes")
        covers.append("lint --unsafe-fixes")
    fmt = rng.choice(LINT_FORMATS)
    args += ["--output-format", fmt]
    return Invocation(
        "inertia-lint",
        (*args, *_paths(tree)),
        tuple(covers),
        writes=True,
        stdout_kind=FORMAT_KIND[fmt],
    )


def _number(rng: random.Random) -> str:
    return rng.choice(SPECIALS) if rng.random() < 0.3 else f"{rng.uniform(-1, 2):.3g}"


def other(
    rng: random.Random, tree: Tree, kind: str | None = None, turn: int | None = None
) -> Invocation | None:
    robot = _file(tree)
    kind = kind or rng.choice(OTHER_KINDS)
    common = _common(rng, tree)
    paths = _paths(tree)
    if kind == "diff":
        unsafe = ["--unsafe-fixes"] if rng.random() < 0.5 else []
        return Invocation(
            "inertia-lint",
            ("--diff", *unsafe, *common, *paths),
            ("lint --diff",),
            stdout_kind="diff",
        )
    if kind == "fill-diff":
        return Invocation(
            "inertia-fill",
            ("--diff", "--fix", rng.choice(FILL_MODES), *common, *paths),
            ("fill --diff",),
            stdout_kind="diff",
        )
    if kind == "fill-check":
        return Invocation(
            "inertia-fill",
            ("--check", "--fix", rng.choice(FILL_MODES), *common, *paths),
            ("fill --check",),
        )
    if kind == "rules":
        fmt = rng.choice(["text", "json"])
        return Invocation(
            "inertia-kit",
            ("rules", "--output-format", fmt),
            (f"rules --output-format {fmt}",),
            stdout_kind=fmt,
        )
    if kind == "explain":
        code = rng.choice(
            [r.CODE for r in catalog.RULES] + ["IN999", "placeholder-inertia", "", "in012"]
        )
        return Invocation("inertia-lint", ("--explain", code), ("lint --explain",))
    if kind == "mass":
        shapes = sorted(MASS_SHAPES)
        shape = rng.choice(shapes) if turn is None else shapes[turn % len(shapes)]
        args = ["mass", shape]
        for flag, count in MASS_SHAPES[shape]:
            args += [flag, *(_number(rng) for _ in range(count))]
        roll = rng.random()
        if roll < 0.4:
            args += ["--density", _number(rng)]
        elif roll < 0.6:
            args += ["--mass", _number(rng)]
        elif roll < 0.7:
            args += ["--material", rng.choice(["steel", "wood", "bogus"])]
        for flag in ("--xyz", "--rpy", "--about", "--about-rpy"):
            if rng.random() < 0.2:
                args += [flag, *(_number(rng) for _ in range(3))]
        fmt = rng.choice(["text", "json"])
        return Invocation(
            "inertia-kit", (*args, "--format", fmt), (f"mass {shape}",), stdout_kind=fmt
        )
    if kind == "mesh":
        meshes = [
            p
            for p in tree.work_files()
            if PurePosixPath(p).suffix.lower() in (".stl", ".obj", ".dae", ".ply", ".glb")
        ]
        candidates = [
            k[len("work/") :]
            for k, n in tree.nodes.items()
            if k.startswith("work/") and n.kind in ("link", "fifo", "sparse")
        ]
        target = rng.choice(meshes or candidates or [robot or "missing.stl"])
        args = ["mass", "mesh", target]
        if rng.random() < 0.3:
            args += ["--scale", rng.choice(["0.001", "1", "0", "-1", "nan"])]
        if rng.random() < 0.3:
            args += ["--density", _number(rng)]
        fmt = rng.choice(["text", "json"])
        return Invocation("inertia-kit", (*args, "--format", fmt), ("mass mesh",), stdout_kind=fmt)
    if robot is None:
        return None
    if kind in ("report", "lumped"):
        fmt = rng.choice(["text", "markdown", "json"])
        args = ["report", "--format", fmt, *common]
        covers = [f"report --format {fmt}"]
        if kind == "lumped":
            args += ["--lumped", "--engine", rng.choice(["all", "all", "mujoco", "drake,kdl"])]
            covers.append("report --lumped")
        return Invocation(
            "inertia-kit",
            (*args, robot),
            tuple(covers),
            stdout_kind="json" if fmt == "json" else "text",
        )
    if kind == "view":
        args = ["view", "-o", "review.html", *common]
        if rng.random() < 0.3:
            args += ["--engine", "all"]
        if rng.random() < 0.1:
            args += ["--triangle-budget", rng.choice(["1", "100", "1000000"])]
        return Invocation(
            "inertia-kit", (*args, robot), ("view -o",), output="review.html", output_kind="html"
        )
    if kind == "fill-o":
        return Invocation(
            "inertia-fill",
            ("--fix", rng.choice(FILL_MODES), "-o", "filled.urdf", *common, robot),
            ("fill -o",),
            output="filled.urdf",
            output_kind="robot",
        )
    if kind == "stdin-lint":
        fmt = rng.choice(LINT_FORMATS)
        name = ["--stdin-filename", robot] if rng.random() < 0.7 else []
        # `fix = true` in a configuration makes `lint -` print the fixed text, not the format
        # (as ruff does): lint --fix - has its own kind
        no_fix = ["--no-fix"] if config_fixes(tree) else []
        return Invocation(
            "inertia-lint",
            ("--output-format", fmt, *no_fix, *name, "-"),
            ("lint -",),
            stdin=robot,
            stdout_kind=FORMAT_KIND[fmt],
        )
    name = ["--stdin-filename", robot] if rng.random() < 0.7 else []
    if kind == "stdin-fill":
        return Invocation(
            "inertia-fill",
            ("--fix", rng.choice(FILL_MODES), *name, "-"),
            ("fill -",),
            stdin=robot,
            stdout_kind="robot",
        )
    return Invocation(
        "inertia-lint",
        ("--fix", "--unsafe-fixes", *name, "-"),
        ("lint --fix -",),
        stdin=robot,
        stdout_kind="robot",
    )


def every(index: int, share: float, offset: int) -> bool:
    """One input in ``1/share``, spread evenly by the index (a small run covers it too)."""
    return share > 0 and index % max(1, round(1 / share)) == offset % max(1, round(1 / share))


def make_plan(
    rng: random.Random,
    tree: Tree,
    *,
    index: int,
    real_share: float,
    interrupt_share: float,
    concurrent_share: float,
) -> Plan:
    """
    The runs of input ``index``: the lint format, the writer and the other command go round
    their lists with the index (every one is covered by a few dozen inputs), the options are
    drawn.
    """
    plan = Plan()
    plan.plain.append(lint(rng, tree, LINT_FORMATS[index % len(LINT_FORMATS)]))
    kind = OTHER_KINDS[index % len(OTHER_KINDS)]
    if tree.get("review.html") is not None:  # links planted at the outputs: write them
        kind = rng.choice(["view", "fill-o", kind])
    extra = other(rng, tree, kind, turn=index // len(OTHER_KINDS))
    if extra is not None:
        plan.plain.append(extra)
    if rng.random() < 0.85:
        # by index // 3: not in step with the every-fifth interrupted input
        plan.writers.append(writer(rng, tree, WRITER_KINDS[index // 3 % len(WRITER_KINDS)]))
    if every(index, real_share, 1):
        # each program in turn, as installed: the console script in a process of its own
        period = max(1, round(1 / real_share))
        wanted = PROGRAMS[index // period % len(PROGRAMS)]
        runs = plan.plain + plan.writers
        if not any(i.program == wanted for i in runs):
            made = {
                "inertia-lint": lambda: lint(rng, tree),
                "inertia-fill": lambda: writer(rng, tree, "fill"),
                "inertia-kit": lambda: other(rng, tree, "mass"),
            }[wanted]()
            runs = [made]
        pick = rng.choice([i for i in runs if i.program == wanted] or runs)
        real = dataclasses.replace(pick, real=True)
        (plan.writers if real.writes else plan.plain).append(real)
    # a plain lint that a configuration turns into a writer is checked as one
    plan.writers += [i for i in plan.plain if i.writes]
    plan.plain = [i for i in plan.plain if not i.writes]
    if every(index, interrupt_share, 2):
        # one more writer, the kind that edits most robots: fill --fix all, or lint's unsafe
        # fixes, in turn; it is SIGKILLed when it edits
        period = max(1, round(1 / interrupt_share))
        if index // period % 2:
            killed = writer(rng, tree, "unsafe")
        else:
            killed = Invocation(
                "inertia-fill", ("--fix", "all", *_paths(tree)), ("fill --fix all",), writes=True
            )
        plan.writers.append(killed)
        plan.interrupt = killed
    if every(index, concurrent_share, 3) and tree.main != ".":
        plan.concurrent = (writer(rng, tree), writer(rng, tree))
    return plan


#: what a campaign of a few hundred inputs must have run: every command, format and writer
COVERAGE = (
    *(f"lint --output-format {f}" for f in LINT_FORMATS),
    "lint --engine all", "lint --statistics", "lint -j 2", "lint -o", "lint -", "lint --explain",
    "lint --fix", "lint --unsafe-fixes", "lint --add-noqa", "lint --diff", "lint --fix -",
    *(f"fill --fix {m}" for m in FILL_MODES),
    "fill --diff", "fill --check", "fill -o", "fill -",
    "report --format text", "report --format markdown", "report --format json", "report --lumped",
    *(f"mass {s}" for s in MASS_SHAPES), "mass mesh", "view -o",
    "rules --output-format text", "rules --output-format json",
    "real inertia-lint", "real inertia-fill", "real inertia-kit",
    "interrupted inertia-fill", "interrupted inertia-lint", "concurrent writers",
)  # fmt: skip
