"""
The checks of one input, each on fresh copies of it (a new root folder materialised from the
tree for every run, so no run sees another's writes):

- :func:`plain`: a command that writes no robot file: its outcome, its streams, its ``-o``
  output, and a folder it left as it was (but for ``-o``);
- :func:`writer`: a command that edits robot files in place: only robot files change, each
  still parses if it did, and a second run changes nothing;
- :func:`interrupted`: the writer SIGKILLed at a random moment: each file is the old one or
  the complete new one;
- :func:`concurrent`: two writers at once: the end state is one that running them one after
  the other (in some order, or one refusing) gives, and every file parses.
"""

from __future__ import annotations

import os
import random
import stat
from dataclasses import dataclass, field
from pathlib import Path

from kit import remove_tree

from fuzz import execute
from fuzz.checks import (
    Failure,
    _injected,
    _unparsable,
    check_outcome,
    check_tree,
    is_robot,
    label,
    parses,
)
from fuzz.execute import Limits, Outcome
from fuzz.plan import Invocation
from fuzz.tree import WORK, Tree, changes, entries, snapshot

State = frozenset  # of (key, bytes): the robot files of a folder


@dataclass
class Context:
    tree: Tree
    base: Path  # this input's folder: its roots are made below it
    limits: Limits
    rng: random.Random
    runs: list[tuple[str, float, float, float]] = field(default_factory=list)  # label, s, cpu s, MB

    def fresh(self, name: str) -> Path:
        root = self.base / name
        remove(root)
        execute.materialise(self.tree, root)
        return root

    def run(self, invocation: Invocation, root: Path, **kw) -> Outcome:
        outcome = execute.run(invocation, root, self.tree, self.limits, **kw)
        self.record(invocation, outcome)
        return outcome

    def record(self, invocation: Invocation, outcome: Outcome) -> None:
        self.runs.append((label(invocation), outcome.seconds, outcome.cpu_seconds, outcome.peak_mb))


def remove(path: Path) -> None:
    """``path`` and all below it, unreadable and 1000-deep folders included."""
    remove_tree(path)


def robot_state(root: Path) -> State:
    """The bytes of every robot file (regular, not a link) in ``root/work``."""
    found = []
    for path, info in entries(root / WORK):
        key = os.path.relpath(path, root)
        if is_robot(key) and stat.S_ISREG(info.st_mode) and info.st_size <= 64 << 20:
            try:
                with open(path, "rb") as stream:
                    found.append((key, stream.read()))
            except OSError:
                continue
    return frozenset(found)


def _output(invocation: Invocation, root: Path, outcome: Outcome) -> list[Failure]:
    """The ``-o`` file of a run that succeeded: it parses as its kind; text has no injection."""
    if not invocation.output or outcome.exit not in (0, 1):
        return []
    path = root / WORK / invocation.output
    if path.is_symlink() or not path.is_file():
        return []
    data = path.read_bytes()
    kind = invocation.output_kind
    if kind == "text":
        what = _injected(data.decode("utf-8", "replace"), controls=True)
        return (
            [
                Failure(
                    "injection",
                    f"{label(invocation)} -o file: {what}",
                    what,
                )
            ]
            if what
            else []
        )
    if kind == "robot":  # it parses if the robot it was written from did
        if parses(data) or not parses(execute_input(root, invocation.args[-1])):
            return []
        return [Failure("unparsable-output", f"{label(invocation)} -o file", "does not parse")]
    problem = _unparsable(data, kind)
    return (
        [Failure("unparsable-output", f"{label(invocation)} -o file", problem)] if problem else []
    )


def _stdout_robot(invocation: Invocation, root: Path, outcome: Outcome) -> list[Failure]:
    """``inertia-fill -`` prints the robot (in its own encoding): it parses if the input did."""
    if invocation.stdout_kind != "robot" or outcome.exit not in (0, 1) or not invocation.stdin:
        return []
    if not parses(execute_input(root, invocation.stdin)) or parses(outcome.stdout):
        return []
    return [
        Failure(
            "unparsable-output", f"{label(invocation)} stdout robot", repr(outcome.stdout[:200])
        )
    ]


def execute_input(root: Path, relative: str) -> bytes | None:
    try:
        return (root / WORK / relative).read_bytes()
    except OSError:
        return None


def plain(ctx: Context, invocation: Invocation) -> list[Failure]:
    root = ctx.fresh("plain")
    before = snapshot(root)
    outcome = ctx.run(invocation, root)
    after = snapshot(root)
    failures = check_outcome(invocation, outcome, ctx.limits)
    failures += check_tree(invocation, before, after, killed=outcome.timed_out)[0]
    failures += _output(invocation, root, outcome)
    failures += _stdout_robot(invocation, root, outcome)
    return failures


@dataclass
class Written:
    """What an uninterrupted writer did: the states before and after, and how long it took."""

    old: State
    new: State
    seconds: float


def writer(ctx: Context, invocation: Invocation) -> tuple[list[Failure], Written | None]:
    root = ctx.fresh("writer")
    old = robot_state(root)
    before = snapshot(root)
    first = ctx.run(invocation, root)
    after = snapshot(root)
    failures = check_outcome(invocation, first, ctx.limits)
    found, edited = check_tree(invocation, before, after, killed=first.timed_out)
    failures += found
    failed = dict(old)
    for key in edited:
        if parses(failed.get(key)) and not parses(execute_input(root, key[len(WORK) + 1 :])):
            failures.append(
                Failure(
                    "unparsable-write", label(invocation), f"{key} parsed before and no longer does"
                )
            )
    if not edited:
        return failures, None
    new = robot_state(root)
    second = ctx.run(invocation, root)
    again = snapshot(root)
    failures += [f for f in check_outcome(invocation, second, ctx.limits) if f not in failures]
    moved = sorted(k for k in changes(after, again) if is_robot(k))
    if moved:
        failures.append(
            Failure(
                "not-idempotent",
                label(invocation),
                f"a second run changed {', '.join(moved)[:200]}",
            )
        )
    return failures, Written(old, new, first.seconds)


def interrupted(
    ctx: Context, invocation: Invocation, written: Written, attempts: int = 2
) -> list[Failure]:
    failures = []
    old, new = dict(written.old), dict(written.new)
    for attempt in range(attempts):
        root = ctx.fresh(f"killed{attempt}")
        before = snapshot(root)
        # most kills near the end of the run, where the write is
        share = ctx.rng.choice(
            [ctx.rng.uniform(0, 1.1), ctx.rng.uniform(0.8, 1.02), ctx.rng.uniform(0.93, 1.0)]
        )
        outcome = ctx.run(invocation, root, kill_after=max(written.seconds * share, 0.001))
        state = dict(robot_state(root))
        for key in old.keys() | new.keys() | state.keys():
            if state.get(key) not in (old.get(key), new.get(key)):
                failures.append(
                    Failure(
                        "interrupted-partial",
                        label(invocation),
                        f"{key} after SIGKILL at {share:.2f} of the run",
                    )
                )
        found = check_tree(invocation, before, snapshot(root), killed=True)[0]
        failures += [f for f in found if f.kind in ("write-outside", "changed-input")]
        if outcome.exit is not None:  # it finished first: its outcome counts as any run's
            failures += check_outcome(invocation, outcome, ctx.limits)
    return failures


def concurrent(ctx: Context, first: Invocation, second: Invocation) -> list[Failure]:
    """Both writers at once; the end state against those of the sequential orders."""
    failures: list[Failure] = []
    orders = ([], [first], [second], [first, second], [second, first])
    states = set()
    for order in orders:
        root = ctx.fresh("sequential")
        for invocation in order:
            ctx.run(invocation, root)
        states.add(robot_state(root))
    root = ctx.fresh("concurrent")
    original = dict(robot_state(root))
    runs = [
        execute.start(inv, root, ctx.tree, ctx.limits, streams=name)
        for inv, name in ((first, "a"), (second, "b"))
    ]
    outcomes = [execute.finish(run, ctx.limits, reap=False) for run in runs]
    execute.reap_orphans()
    for invocation, outcome in zip((first, second), outcomes, strict=False):
        ctx.record(invocation, outcome)
        # told as concurrent: what two writers at once do to each other (issue 19 item 1)
        failures += [
            Failure(f.kind, f"{f.detail} (concurrent)", f.message)
            for f in check_outcome(invocation, outcome, ctx.limits)
            if f.kind != "injection"
        ]
    final = robot_state(root)
    pair = f"{label(first)} + {label(second)}"
    if final not in states:
        failures.append(
            Failure("concurrent-state", pair, "the end state is none that a sequential order gives")
        )
    for key, data in final:
        if parses(original.get(key)) and not parses(data):
            failures.append(
                Failure("unparsable-write", f"concurrent {pair}", f"{key} no longer parses")
            )
    return failures
