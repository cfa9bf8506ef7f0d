"""
A fuzz campaign: inputs ``0 .. N-1`` of a seed, each generated from ``random.Random(f"{seed}/
{index}")`` (fuzz.seeds, fuzz.mutate), run through its plan (fuzz.plan, fuzz.procedures) in
worker processes (fresh from a forkserver, each importing everything once, then forking a run
per invocation: a run's peak memory is its own, whatever the caller holds); failures shrunk
(fuzz.shrink) and saved as reproducer folders; a summary by class and signature, with the
runs' peak time and memory and the inputs per second.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import random
import re
import shlex
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

from fuzz import execute, procedures
from fuzz.checks import Failure
from fuzz.execute import Limits
from fuzz.layouts import add_outside
from fuzz.mutate import mutate
from fuzz.plan import Invocation, every, make_plan
from fuzz.seeds import seed as seed_tree
from fuzz.shrink import shrink
from fuzz.tree import WORK, Tree, dumps


@dataclass(frozen=True)
class Profile:
    """How a campaign draws and runs its inputs."""

    big_links: tuple[int, ...] = (300, 1000, 2000, 5000)
    real_share: float = 0.03  # runs through the installed console scripts
    interrupt_share: float = 0.2  # the first writer that edits is SIGKILLed at a random moment
    concurrent_share: float = 0.03  # two writers at once
    limits: Limits = Limits()  # noqa: RUF009 - frozen: one shared default is fine
    shrink_seconds: float = 120.0  # per failure signature and worker; 0: no shrinking
    shrink_attempts: int = 250


#: the bounded run of the test suite: small robots, xacro expansions cut at 5 s, no shrinking
CI = Profile(
    big_links=(300, 1000),
    real_share=0.05,
    interrupt_share=0.2,
    concurrent_share=0.05,
    limits=Limits(xacro_limits="timeout=5"),
    shrink_seconds=0.0,
)
#: the long run (INERTIA_KIT_FUZZ_INPUTS): everything at its defaults
LONG = Profile()


def generate(seed: int | str, index: int, profile: Profile) -> tuple[Tree, random.Random]:
    rng = random.Random(f"{seed}/{index}")
    tree = seed_tree(rng, profile.big_links)
    add_outside(tree)
    # an input whose writers are SIGKILLed or run two at once: mostly whole robots, which
    # writers edit (what is to be interrupted must be written)
    writing = every(index, profile.interrupt_share, 2) or every(index, profile.concurrent_share, 3)
    mutate(rng, tree, rng.choice([0, 0, 0, 1] if writing else [0, 1, 1, 1, 2, 2, 3, 4]))
    return tree, rng


@dataclass
class Found:
    """One failure of one input: the command and the check that showed it."""

    failure: Failure
    invocation: Invocation
    procedure: str  # plain | writer | interrupted | concurrent
    reproducer: str | None = None


@dataclass
class InputResult:
    index: int
    notes: list[str]
    coverage: list[str]
    found: list[Found]
    runs: list[tuple[str, float, float, float]]
    seconds: float


def check_input(
    seed: int | str, index: int, profile: Profile, base: Path, out: Path | None, shrunk: set[str]
) -> InputResult:
    started = time.monotonic()
    tree, rng = generate(seed, index, profile)
    plan = make_plan(
        rng,
        tree,
        index=index,
        real_share=profile.real_share,
        interrupt_share=profile.interrupt_share,
        concurrent_share=profile.concurrent_share,
    )
    ctx = procedures.Context(tree, base / f"input-{index}", profile.limits, rng)
    found: list[Found] = []
    coverage: list[str] = []

    def add(failures: list[Failure], invocation: Invocation, procedure: str) -> None:
        for failure in failures:
            if all(f.failure.signature != failure.signature for f in found):
                found.append(Found(failure, invocation, procedure))

    for invocation in plan.plain:
        coverage += invocation.coverage()
        add(procedures.plain(ctx, invocation), invocation, "plain")
    for invocation in plan.writers:
        coverage += invocation.coverage()
        failures, written = procedures.writer(ctx, invocation)
        add(failures, invocation, "writer")
        if invocation is plan.interrupt and written is not None:
            coverage.append(f"interrupted {invocation.program}")
            add(procedures.interrupted(ctx, invocation, written), invocation, "interrupted")
    if plan.concurrent:
        first, second = plan.concurrent
        coverage.append("concurrent writers")
        add(procedures.concurrent(ctx, first, second), first, "concurrent")
    procedures.remove(ctx.base)
    if out is not None:
        for item in found:
            if item.procedure in ("plain", "writer") and item.failure.signature not in shrunk:
                shrunk.add(item.failure.signature)
                item.reproducer = str(save_reproducer(out, seed, index, tree, item, profile, base))
            elif item.failure.signature not in shrunk:
                shrunk.add(item.failure.signature)
                item.reproducer = str(
                    save_reproducer(out, seed, index, tree, item, profile, base, shrinking=False)
                )
    return InputResult(index, tree.notes, coverage, found, ctx.runs, time.monotonic() - started)


# --- reproducers -----------------------------------------------------------------------------


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("_")[:80] or "x"


def _restricted(node) -> bool:
    """A node whose mode denies its owner something: root must obey modes to see the bug."""
    if node.mode is None:
        return False
    needed = 0o700 if node.kind == "dir" else 0o600
    return node.mode & needed != needed


def save_reproducer(
    out: Path,
    seed,
    index: int,
    tree: Tree,
    item: Found,
    profile: Profile,
    base: Path,
    shrinking: bool = True,
) -> Path:
    """The input (shrunk while it fails the same way), its command and its output, in a folder."""
    signature = item.failure.signature
    small, attempts = tree, 0
    if shrinking and profile.shrink_seconds > 0:
        slow = item.failure.kind in ("timeout", "memory", "huge-output")
        ctx_base = base / f"shrink-{index}"

        def fails(candidate: Tree) -> bool:
            ctx = procedures.Context(candidate, ctx_base, profile.limits, random.Random(0))
            if item.procedure == "plain":
                failures = procedures.plain(ctx, item.invocation)
            else:
                failures = procedures.writer(ctx, item.invocation)[0]
            return any(f.signature == signature for f in failures)

        # a run that hangs or grows costs the time limit per attempt: kept whole
        small, attempts = shrink(
            tree,
            fails,
            seconds=profile.shrink_seconds,
            attempts=0 if slow else profile.shrink_attempts,
        )
        procedures.remove(ctx_base)
    folder = (
        out
        / "reproducers"
        / _slug(item.failure.kind)
        / _slug(item.failure.detail)
        / f"input-{index}"
    )
    procedures.remove(folder)
    folder.mkdir(parents=True)
    (folder / "input.json").write_text(dumps(small))
    huge = any(n.kind == "sparse" for n in small.nodes.values())
    if not huge:
        small.materialise(folder / "tree")
    env = "".join(f"{k}={shlex.quote(v)} " for k, v in sorted(small.env.items()))
    rebuild = ""
    if huge:  # a sparse file of gigabytes: made when needed
        paths = f"{shlex.quote(str(folder / 'input.json'))} {shlex.quote(str(folder / 'tree'))}"
        rebuild = f"PYTHONPATH=tests python -m fuzz --materialise {paths}\n"
    obeying = ""
    if os.geteuid() == 0 and any(_restricted(n) for n in small.nodes.values()):
        drop = "-dac_override,-dac_read_search,-fowner"
        obeying = f"setpriv --inh-caps={drop} --bounding-set={drop} "  # root obeys file modes
    (folder / "command.sh").write_text(
        "#!/bin/sh\n"
        f"# {signature}\n# {item.failure.message[:300]!r}\n"
        f"# input {index} of seed {seed} ({item.procedure}; shrunk in {attempts} attempts): "
        f"{'; '.join(tree.notes)[:500]}\n"
        f'{rebuild}cd "$(dirname "$0")/tree/{WORK}" && INERTIA_KIT_TRACEBACK=1 '
        f"{env}{obeying}{item.invocation.line()}\n"
    )
    return folder


# --- the campaign ----------------------------------------------------------------------------

_WORKER: dict = {}


def _start_worker(seed, profile: Profile, base: str, out: str | None) -> None:
    execute.preload()  # a worker starts fresh (forkserver): imports once, before any run
    execute.become_subreaper()
    _WORKER.update(
        seed=seed,
        profile=profile,
        base=Path(base) / f"worker-{os.getpid()}",
        out=Path(out) if out else None,
        shrunk=set(),
    )


def _work(index: int) -> InputResult:
    w = _WORKER
    try:
        return check_input(w["seed"], index, w["profile"], w["base"], w["out"], w["shrunk"])
    except Exception as error:  # the harness itself: an input it cannot even run is a result
        import traceback

        failure = Failure("harness-error", type(error).__name__, traceback.format_exc()[-600:])
        return InputResult(
            index, [], [], [Found(failure, Invocation("harness", (), ()), "harness")], [], 0.0
        )


@dataclass
class Summary:
    seed: str
    inputs: int
    seconds: float
    runs: int
    signatures: dict[str, dict] = field(default_factory=dict)  # signature -> count, example
    coverage: Counter = field(default_factory=Counter)
    slowest: tuple[float, str, int] = (0.0, "", -1)  # seconds, command, input
    most_cpu: tuple[float, str, int] = (0.0, "", -1)  # CPU seconds, command, input: the limit
    seconds_by_command: Counter = field(default_factory=Counter)
    slow_inputs: list[tuple[float, int, str]] = field(default_factory=list)  # the 10 slowest
    hungriest: tuple[float, str, int] = (0.0, "", -1)  # peak MB, command, input

    @property
    def inputs_per_second(self) -> float:
        return self.inputs / self.seconds if self.seconds else 0.0

    def add(self, result: InputResult) -> None:
        self.runs += len(result.runs)
        self.coverage.update(set(result.coverage))
        self.slow_inputs = sorted(
            [*self.slow_inputs, (result.seconds, result.index, "; ".join(result.notes)[:160])],
            reverse=True,
        )[:10]
        for command, seconds, cpu, peak in result.runs:
            self.seconds_by_command[command] += seconds
            if seconds > self.slowest[0]:
                self.slowest = (seconds, command, result.index)
            if cpu > self.most_cpu[0]:
                self.most_cpu = (cpu, command, result.index)
            if peak > self.hungriest[0]:
                self.hungriest = (peak, command, result.index)
        for item in result.found:
            entry = self.signatures.setdefault(
                item.failure.signature,
                {
                    "kind": item.failure.kind,
                    "count": 0,
                    "inputs": [],
                    "message": item.failure.message,
                    "command": item.invocation.line(),
                    "procedure": item.procedure,
                    "notes": result.notes,
                    "reproducer": None,
                },
            )
            entry["count"] += 1
            if len(entry["inputs"]) < 20:
                entry["inputs"].append(result.index)
            entry["reproducer"] = entry["reproducer"] or item.reproducer

    def by_kind(self) -> Counter:
        kinds: Counter = Counter()
        for entry in self.signatures.values():
            kinds[entry["kind"]] += entry["count"]
        return kinds

    def text(self, known=None) -> str:
        lines = [
            f"fuzz seed {self.seed}: {self.inputs} inputs, {self.runs} runs in "
            f"{self.seconds:.0f} s ({self.inputs_per_second:.2f} inputs/s)",
            f"slowest run {self.slowest[0]:.2f} s wall ({self.slowest[1]}, input "
            f"{self.slowest[2]}); most CPU {self.most_cpu[0]:.2f} s ({self.most_cpu[1]}, input "
            f"{self.most_cpu[2]}); peak memory {self.hungriest[0]:.0f} MB ({self.hungriest[1]}, "
            f"input {self.hungriest[2]})",
        ]
        kinds = self.by_kind()
        lines.append(
            "failures by class: "
            + (", ".join(f"{k} {n}" for k, n in sorted(kinds.items())) or "none")
        )
        for signature, entry in sorted(
            self.signatures.items(), key=lambda kv: (kv[1]["kind"], -kv[1]["count"])
        ):
            why = known(signature) if known else None
            tag = f" [known open: {why}]" if why else ""
            lines.append(f"  {entry['count']:5d}  {signature}{tag}")
            lines.append(f"         e.g. input {entry['inputs'][0]}: {entry['command'][:160]}")
            lines.append(f"         {entry['message'][:200]!r}")
            if entry["reproducer"]:
                lines.append(f"         reproducer: {entry['reproducer']}")
        return "\n".join(lines)

    def to_json(self) -> dict:
        return {
            "seed": self.seed,
            "inputs": self.inputs,
            "seconds": self.seconds,
            "runs": self.runs,
            "inputs_per_second": self.inputs_per_second,
            "slowest": self.slowest,
            "hungriest": self.hungriest,
            "by_kind": dict(self.by_kind()),
            "coverage": dict(sorted(self.coverage.items())),
            "seconds_by_command": dict(self.seconds_by_command.most_common()),
            "most_cpu": list(self.most_cpu),
            "slow_inputs": self.slow_inputs,
            "signatures": self.signatures,
        }


def run_campaign(
    seed: int | str,
    indices: list[int],
    profile: Profile,
    *,
    workers: int,
    out: Path | None = None,
    progress: bool = False,
) -> Summary:
    execute.preload()
    base = Path(tempfile.mkdtemp(prefix="inertia-kit-fuzz-"))
    started = time.monotonic()
    summary = Summary(str(seed), len(indices), 0.0, 0)
    try:
        if workers <= 1:
            _start_worker(seed, profile, str(base), str(out) if out else None)
            results = map(_work, indices)
            pool = None
        else:
            # workers from a fresh forkserver, not forked from this process: a run's peak
            # memory counts the pages it inherits, and a pytest worker that ran other tests
            # before may hold a gigabyte (every run then "over 1 GB", by another test's heap)
            pool = multiprocessing.get_context("forkserver").Pool(
                workers,
                initializer=_start_worker,
                initargs=(seed, profile, str(base), str(out) if out else None),
            )
            results = pool.imap_unordered(_work, indices, chunksize=1)
        for done, result in enumerate(results, 1):
            summary.add(result)
            if progress and (done % 50 == 0 or done == len(indices)):
                rate = done / (time.monotonic() - started)
                print(
                    f"fuzz: {done}/{len(indices)} inputs, {rate:.2f}/s, "
                    f"{sum(summary.by_kind().values())} failures",
                    file=sys.stderr,
                    flush=True,
                )
        if pool is not None:
            pool.close()
            pool.join()
    finally:
        procedures.remove(base)
    summary.seconds = time.monotonic() - started
    if out is not None:
        out.mkdir(parents=True, exist_ok=True)
        (out / "summary.json").write_text(json.dumps(summary.to_json(), indent=1, default=str))
    return summary
