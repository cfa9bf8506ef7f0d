"""
Two writers at once on one robot: does every run end in a state that running them one after
the other gives, and does every file still parse?

A *writer* is a command that edits robot files in place (:data:`WRITERS`: ``inertia-fill`` in
two modes, ``inertia-lint --fix`` with and without unsafe fixes, ``inertia-lint --add-noqa``).
A *project* is a package whose robot file the writers are given (:data:`PROJECTS`: a URDF robot,
and a xacro robot whose included fragment the writers edit too); every writer changes it.

For a pair ``(a, b)`` the reference states are computed on copies: ``a`` alone, ``b`` alone,
``a`` then ``b``, ``b`` then ``a``. A concurrent run starts ``a`` and ``b`` as two processes on
one copy, ``b`` ``offset`` seconds after ``a`` (negative: before), and takes the final state (the
bytes of every robot file). It is *sequential* when it is ``a`` then ``b`` or ``b`` then ``a``,
or one writer alone when the other refused with exit 2 ("the file changed while it was being
processed"): a writer that says it wrote must not have been overwritten. It *parses* when every
robot file is well-formed XML.

Used by ``tests/cli/test_cli_concurrent_writers.py`` (a few runs per pair) and
``benchmarks/concurrency.py`` (``INERTIA_KIT_CONCURRENCY_RUNS``, 50 per pair, the table).
"""

from __future__ import annotations

import itertools
import os
import random
import shutil
import subprocess
import sys
import tempfile
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

from kit import write

#: name -> the command line after ``python -m inertia_kit`` (the robot file is appended)
WRITERS: dict[str, tuple[str, ...]] = {
    "fill": ("fill",),
    "fill-all": ("fill", "--fix", "all"),
    "lint-fix": ("lint", "--fix", "--output-format", "concise"),
    "lint-unsafe": ("lint", "--fix", "--unsafe-fixes", "--output-format", "concise"),
    "add-noqa": ("lint", "--add-noqa"),
}

#: what a writer that lost the race says (exit 2)
CHANGED = "the file changed while it was being processed"

_LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'
_PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>race_description</name><version>0.0.0</version>
<description>d</description><maintainer email="a@b.c">a</maintainer><license>MIT</license>
</package>
"""

# every writer changes it: `arm` has no <inertial> (fill, unsafe fixes, add-noqa), `plate` has
# its product sign flipped (a safe fix; fill --fix all recomputes it), and a comment suppresses
# nothing (its removal is a safe fix)
URDF = f"""<?xml version="1.0"?>
<robot name="race">
  <link name="world"/>
  <joint name="fixed_base" type="fixed">
    <parent link="world"/>
    <child link="base"/>
  </joint>
  <!-- inertia-lint: ignore[IN012] -->
  <link name="base">
    <inertial>
      <mass value="6"/>
      <inertia ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.04"/>
    </inertial>
    <collision>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </collision>
  </link>
  <joint name="j_plate" type="revolute">
    <parent link="base"/>
    <child link="plate"/>
    <axis xyz="0 0 1"/>
    {_LIMIT}
  </joint>
  <link name="plate">
    <inertial>
      <mass value="2"/>
      <inertia ixx="0.0133333" ixy="0.00866025" ixz="0" iyy="0.0233333" iyz="0" izz="0.0333333"/>
    </inertial>
    <collision>
      <origin rpy="0 0 0.5235988"/>
      <geometry><box size="0.4 0.2 0.1"/></geometry>
    </collision>
  </link>
  <joint name="j_arm" type="revolute">
    <parent link="plate"/>
    <child link="arm"/>
    <origin xyz="0 0 0.1"/>
    <axis xyz="0 1 0"/>
    {_LIMIT}
  </joint>
  <link name="arm">
    <collision>
      <origin xyz="0 0 0.15"/>
      <geometry><cylinder radius="0.03" length="0.3"/></geometry>
    </collision>
  </link>
</robot>
"""

_XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

# the fragment: a wheel macro without <inertial> (used twice, alike: filled once in its body)
# and a plate macro whose product sign is flipped (a safe fix in its body)
PARTS = f"""<?xml version="1.0"?>
<robot {_XACRO}>
  <xacro:macro name="wheel" params="name parent y">
    <joint name="${{name}}_joint" type="continuous">
      <parent link="${{parent}}"/>
      <child link="${{name}}"/>
      <origin xyz="0 ${{y}} 0" rpy="-1.5707963 0 0"/>
      <axis xyz="0 0 1"/>
    </joint>
    <link name="${{name}}">
      <collision>
        <geometry><cylinder radius="0.05" length="0.03"/></geometry>
      </collision>
    </link>
  </xacro:macro>

  <xacro:macro name="plate" params="parent">
    <joint name="plate_joint" type="revolute">
      <parent link="${{parent}}"/>
      <child link="plate"/>
      <origin xyz="0 0 0.1"/>
      <axis xyz="0 0 1"/>
      {_LIMIT}
    </joint>
    <link name="plate">
      <inertial>
        <mass value="2"/>
        <inertia ixx="0.0133333" ixy="0.00866025" ixz="0" iyy="0.0233333" iyz="0" izz="0.0333333"/>
      </inertial>
      <collision>
        <origin rpy="0 0 0.5235988"/>
        <geometry><box size="0.4 0.2 0.1"/></geometry>
      </collision>
    </link>
  </xacro:macro>
</robot>
"""

ROBOT_XACRO = f"""<?xml version="1.0"?>
<robot name="race" {_XACRO}>
  <xacro:include filename="parts.xacro"/>
  <link name="world"/>
  <joint name="fixed_base" type="fixed">
    <parent link="world"/>
    <child link="base"/>
  </joint>
  <!-- inertia-lint: ignore[IN012] -->
  <link name="base">
    <inertial>
      <mass value="6"/>
      <inertia ixx="0.025" ixy="0" ixz="0" iyy="0.025" iyz="0" izz="0.04"/>
    </inertial>
    <collision>
      <geometry><box size="0.2 0.2 0.1"/></geometry>
    </collision>
  </link>
  <xacro:wheel name="left" parent="base" y="0.12"/>
  <xacro:wheel name="right" parent="base" y="-0.12"/>
  <xacro:plate parent="base"/>
</robot>
"""


@dataclass(frozen=True)
class Project:
    """
    A package to copy: its robot files (name -> text), the robot file the writers are given,
    and, for a real package, the folder whose other files (meshes, ``package.xml``) are linked
    into each copy, and options every writer takes (``--package-path``).
    """

    name: str
    files: dict[str, str]
    robot: str
    assets: Path | None = None
    options: tuple[str, ...] = ()

    @classmethod
    def from_folder(cls, folder: Path, robot: str, options: tuple[str, ...] = ()) -> Project:
        """A real package: its ``.urdf`` and ``.xacro`` files copied, the rest linked."""
        files = {
            str(p.relative_to(folder)): p.read_text(encoding="utf-8")
            for p in sorted(folder.rglob("*"))
            if p.suffix.lower() in (".urdf", ".xacro") and p.is_file()
        }
        return cls(folder.name, files, robot, folder, options)

    def copy(self, into: Path) -> Path:
        """The project written into the new folder ``into`` (a package in a git repository)."""
        (into / ".git").mkdir(parents=True)  # the repository a writer stays in
        for name, text in self.files.items():
            write(into / name, text)
        if self.assets is None:
            write(into / "package.xml", _PACKAGE)
            return into
        for original in self.assets.rglob("*"):
            copy = into / original.relative_to(self.assets)
            if original.is_file() and not copy.exists():
                copy.parent.mkdir(parents=True, exist_ok=True)
                copy.symlink_to(original.resolve())
        return into


PROJECTS = {
    "urdf": Project("urdf", {"urdf/race.urdf": URDF}, "urdf/race.urdf"),
    "xacro": Project(
        "xacro",
        {"urdf/race.urdf.xacro": ROBOT_XACRO, "urdf/parts.xacro": PARTS},
        "urdf/race.urdf.xacro",
    ),
}

State = tuple[tuple[str, bytes], ...]


def state(root: Path, project: Project) -> State:
    """The bytes of every robot file of ``project`` under ``root`` (missing: empty)."""
    return tuple(
        (name, (root / name).read_bytes() if (root / name).exists() else b"")
        for name in sorted(project.files)
    )


def parses(final: State) -> bool:
    """Whether every file of ``final`` is well-formed XML."""
    from lxml import etree

    for _, data in final:
        try:
            etree.fromstring(data, etree.XMLParser(resolve_entities=False, no_network=True))
        except etree.XMLSyntaxError:
            return False
    return True


def command(writer: str, project: Project) -> list[str]:
    return [sys.executable, "-m", "inertia_kit", *WRITERS[writer], *project.options, project.robot]


def _environment() -> dict[str, str]:
    env = dict(os.environ)
    env.setdefault("INERTIA_KIT_NO_CACHE", "1")
    env["NO_COLOR"] = "1"
    return env


@dataclass(frozen=True)
class Outcome:
    code: int
    stderr: str

    @property
    def refused(self) -> bool:
        """Lost the race: exit 2 saying the file changed (and so wrote nothing)."""
        return self.code == 2 and CHANGED in self.stderr


def run_writer(
    writer: str, root: Path, project: Project, timeout: float = 120, in_process: bool = False
) -> Outcome:
    """
    ``writer`` on the project's robot in ``root``, to its end: a process of its own, or, with
    ``in_process``, in this one (faster, for the references of a short run).
    """
    if in_process:
        return _in_process(writer, root, project)
    done = subprocess.run(
        command(writer, project),
        cwd=root,
        env=_environment(),
        capture_output=True,
        text=True,
        timeout=timeout,
    )
    return Outcome(done.returncode, done.stderr)


def _in_process(writer: str, root: Path, project: Project) -> Outcome:
    from click.testing import CliRunner

    from inertia_kit.cli import main

    here = os.getcwd()
    os.chdir(root)
    try:
        result = CliRunner().invoke(main, [*WRITERS[writer], *project.options, project.robot])
    finally:
        os.chdir(here)
    if result.exception is not None and not isinstance(result.exception, SystemExit):
        raise result.exception
    return Outcome(result.exit_code, result.stderr)


@dataclass
class References:
    """The states of one project that writers run one after the other give."""

    initial: State
    alone: dict[str, State] = field(default_factory=dict)
    ordered: dict[tuple[str, str], State] = field(default_factory=dict)  # (first, then)
    seconds: float = 0.0  # how long one writer's run took, on average

    def allowed(self, a: str, b: str, a_out: Outcome, b_out: Outcome) -> set[State]:
        """The final states some sequential order gives for this run's exits."""
        states = {self.ordered[(a, b)], self.ordered[(b, a)]}
        if b_out.refused:
            states.add(self.alone[a])
        if a_out.refused:
            states.add(self.alone[b])
        if a_out.refused and b_out.refused:
            states.add(self.initial)
        return states


def _put(root: Path, final: State) -> None:
    for name, data in final:
        (root / name).write_bytes(data)


def changing(project: Project, writers: Iterable[str], scratch: Path) -> list[str]:
    """The writers that change ``project`` when run alone (for a real package)."""
    initial = state(project.copy(scratch / "initial"), project)
    found = []
    for number, writer in enumerate(writers):
        root = project.copy(scratch / f"alone-{number}")
        run_writer(writer, root, project)
        if state(root, project) != initial:
            found.append(writer)
    return found


def references(
    project: Project, writers: Iterable[str], scratch: Path, in_process: bool = False
) -> References:
    """Every writer alone, then every writer after each (on a copy of its state)."""
    writers = list(writers)
    fresh = itertools.count()
    runs: list[float] = []

    def ran(writer: str, before: State | None) -> State:
        root = project.copy(scratch / f"ref-{next(fresh)}")
        if before is not None:
            _put(root, before)
        started = time.monotonic()
        outcome = run_writer(writer, root, project, in_process=in_process)
        runs.append(time.monotonic() - started)
        if outcome.code not in (0, 1):
            raise AssertionError(f"{writer} alone: exit {outcome.code}\n{outcome.stderr}")
        return state(root, project)

    refs = References(state(project.copy(scratch / "ref-initial"), project))
    for writer in writers:
        refs.alone[writer] = ran(writer, None)
        if refs.alone[writer] == refs.initial:
            raise AssertionError(f"{writer} changes nothing in the {project.name} project")
    for a, b in itertools.product(writers, repeat=2):
        refs.ordered[(a, b)] = ran(b, refs.alone[a])
    refs.seconds = sum(runs) / len(runs)
    return refs


@dataclass(frozen=True)
class Run:
    """One concurrent run: the offset, both exits, the final state and its verdicts."""

    offset: float
    a: Outcome
    b: Outcome
    final: State
    sequential: bool
    parses: bool

    def told(self) -> str:
        """One line on a run that failed, for the report."""
        last = [(o.stderr.strip().splitlines() or [""])[-1][:100] for o in (self.a, self.b)]
        return f"offset {self.offset:+.3f} s: exits {self.a.code}, {self.b.code}: {last}"


def _start(writer: str, project: Project, root: Path) -> subprocess.Popen:
    return subprocess.Popen(
        command(writer, project),
        cwd=root,
        env=_environment(),
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        text=True,
    )


def race(a: str, b: str, project: Project, refs: References, root: Path, offset: float) -> Run:
    """``a`` and ``b`` at once on a fresh copy in ``root``, ``b`` started ``offset`` s later."""
    project.copy(root)
    processes: list[subprocess.Popen] = [None, None]  # type: ignore[list-item]
    order = (0, 1) if offset >= 0 else (1, 0)
    processes[order[0]] = _start((a, b)[order[0]], project, root)
    time.sleep(abs(offset))
    processes[order[1]] = _start((a, b)[order[1]], project, root)
    outcomes = []
    for process in processes:
        _, err = process.communicate(timeout=300)
        outcomes.append(Outcome(process.returncode, err))
    a_out, b_out = outcomes
    final = state(root, project)
    exits = all(o.code in (0, 1) or o.refused for o in outcomes)
    ok = exits and final in refs.allowed(a, b, a_out, b_out)
    return Run(offset, a_out, b_out, final, ok, parses(final))


@dataclass
class PairReport:
    project: str
    a: str
    b: str
    runs: list[Run] = field(default_factory=list)

    @property
    def distinct(self) -> int:
        return len({run.final for run in self.runs})

    @property
    def sequential(self) -> bool:
        return all(run.sequential for run in self.runs)

    @property
    def parse(self) -> bool:
        return all(run.parses for run in self.runs)

    @property
    def refused(self) -> int:
        return sum(run.a.refused or run.b.refused for run in self.runs)

    def row(self) -> str:
        bad = sum(not run.sequential for run in self.runs)
        return (
            f"{self.project:6} {self.a:12} {self.b:12} {len(self.runs):5} {self.distinct:9} "
            f"{self.refused:8} {'yes' if self.sequential else f'NO ({bad})':>11} "
            f"{'yes' if self.parse else 'NO':>7}"
        )


HEADER = (
    f"{'robot':6} {'writer a':12} {'writer b':12} {'runs':>5} {'distinct':>9} {'refused':>8} "
    f"{'sequential':>11} {'parses':>7}"
)


def offsets(runs: int, spread: float, seed: int) -> list[float]:
    """``runs`` start offsets over ``[-spread, spread]``, each in the middle of its share of
    it (one run: 0, both at once), shuffled."""
    chosen = [-spread + spread * (2 * i + 1) / runs for i in range(runs)]
    random.Random(seed).shuffle(chosen)
    return chosen


def pairs(writers: Iterable[str]) -> list[tuple[str, str]]:
    """Every unordered pair of writers, each writer with itself included."""
    return list(itertools.combinations_with_replacement(list(writers), 2))


def harness(
    runs: int,
    *,
    projects: Iterable[str | Project] = tuple(PROJECTS),
    writers: Iterable[str] = tuple(WRITERS),
    spread: float | None = None,
    scratch: Path | None = None,
    told: Callable[[PairReport], None] | None = None,
    seed: int = 19,
    in_process_references: bool = False,
) -> list[PairReport]:
    """
    ``runs`` concurrent runs of every pair of ``writers`` on every project; ``spread``: the
    largest start offset in seconds (default: about one writer's run, measured as a process).
    ``in_process_references``: the reference states computed in this process (faster).
    """
    writers = list(writers)
    reports = []
    with tempfile.TemporaryDirectory(prefix="inertia-kit-race-") as folder:
        base = Path(folder) if scratch is None else scratch
        count = itertools.count()
        for chosen in projects:
            project = PROJECTS[chosen] if isinstance(chosen, str) else chosen
            name = project.name
            refs = references(project, writers, base / f"{name}-refs", in_process_references)
            width = spread if spread is not None else refs.seconds
            if spread is None and in_process_references:  # one run as a process
                started = time.monotonic()
                run_writer(writers[0], project.copy(base / f"{name}-timed"), project)
                width = time.monotonic() - started
            for a, b in pairs(writers):
                report = PairReport(name, a, b)
                for offset in offsets(runs, width, seed):
                    root = base / f"{name}-run-{next(count)}"
                    report.runs.append(race(a, b, project, refs, root, offset))
                    shutil.rmtree(root, ignore_errors=True)
                reports.append(report)
                if told is not None:
                    told(report)
    return reports
