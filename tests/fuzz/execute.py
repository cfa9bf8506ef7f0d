"""
Running one invocation on a materialised input, as a process of its own with resource limits.

The harness process imports everything once (:func:`preload`) and forks a child per run: the
child makes its own process group, lowers ``RLIMIT_AS`` (a backstop well above the 1 GB the
acceptance allows, so that a runaway run ends in ``MemoryError`` instead of taking the
machine), ``RLIMIT_FSIZE`` (no file, stdout included, past it: a run that writes without bound
gets ``EFBIG``), points its standard streams at files, moves into ``work/`` and calls the click
command in-process (``standalone_mode``, as the console script does) or, for a share of runs,
``exec`` s the installed console script. The parent waits for it up to ``wall_factor`` times
the time limit of wall time (then kills the whole group), judges the limit on the CPU time the
run spent, and reads the peak resident memory from ``wait4`` (the child's and
every descendant's it waited for: the xacro sandbox, ``-j`` workers).

Run as root, the child drops the capabilities that let root read and write any file
(``CAP_DAC_OVERRIDE``, ``CAP_DAC_READ_SEARCH``, ``CAP_FOWNER``), so unreadable files are
unreadable to it, and links to ``/dev/zero`` or ``/dev/null`` point at device nodes made
inside the run's root (a write that replaced the link's target replaces those, never the
machine's).
"""

from __future__ import annotations

import contextlib
import ctypes
import importlib
import io
import locale
import os
import pkgutil
import resource
import select
import signal
import stat
import sys
import sysconfig
import time
import traceback
from dataclasses import dataclass
from pathlib import Path

from kit.permissions import drop_file_capabilities

from fuzz.plan import Invocation
from fuzz.tree import CACHE, HOME, OUTSIDE, WORK, Tree

RUN = "run"  # the folder of a run's standard streams, beside work/
KEEP_BYTES = 32 << 20  # of each stream, read back for the checks


@dataclass(frozen=True)
class Limits:
    seconds: float = 60.0  # CPU time of one run (and of the descendants it waits for)
    #: the run is killed after ``wall_factor * seconds`` of wall time (a hang that spends no
    #: CPU: a FIFO read, a lock); CPU, not wall time, is the limit, so that runs on a machine
    #: shared with other work (the harness runs at nice 19) are not failed for waiting
    wall_factor: float = 4.0
    memory_mb: int = 1024  # the acceptance: peak resident memory of a run
    address_space_mb: int = 3072  # RLIMIT_AS above the harness's own: the backstop
    file_mb: int = 512  # RLIMIT_FSIZE
    xacro_limits: str = ""  # INERTIA_KIT_XACRO_LIMITS for every run ("" the defaults)


@dataclass
class Outcome:
    exit: int | None  # None: killed by a signal (``signal``)
    signal: int | None
    timed_out: bool
    seconds: float
    cpu_seconds: float
    peak_mb: float
    stdout: bytes
    stderr: bytes
    stdout_size: int
    stderr_size: int


# --- the harness process -------------------------------------------------------------------


def preload() -> None:
    """Import every module a command may import, once, before any fork."""
    import inertia_kit

    for module in pkgutil.walk_packages(inertia_kit.__path__, "inertia_kit."):
        with contextlib.suppress(Exception):
            importlib.import_module(module.name)
    for name in (
        "trimesh",
        "xacro",
        "xacro.substitution_args",
        "collada",
        "networkx",
        "fast_simplification",
        "yaml",
        "manifold3d",
        "pathspec",
    ):
        with contextlib.suppress(Exception):
            importlib.import_module(name)
    from inertia_kit.description.urdf import xacro_sandbox

    xacro_sandbox.preload()
    import gc

    gc.collect()
    gc.freeze()  # the children's collections leave the inherited heap alone (no copy on write)


def become_subreaper() -> None:
    """Orphans of a run (a killed run's workers) come back to this process, to be reaped."""
    with contextlib.suppress(Exception):
        ctypes.CDLL(None).prctl(36, 1, 0, 0, 0)  # PR_SET_CHILD_SUBREAPER


def reap_orphans() -> None:
    with contextlib.suppress(ChildProcessError):
        while os.waitpid(-1, os.WNOHANG)[0]:
            pass


AS_ROOT = os.geteuid() == 0
_DEVICES = {"/dev/zero": (1, 5), "/dev/null": (1, 3), "/dev/urandom": (1, 9)}


def materialise(tree: Tree, root: Path) -> None:
    """``tree`` on disk at ``root``, with the run folder; as root, /dev links to our own devices."""
    if AS_ROOT:
        tree = tree.copy()
        for key, node in list(tree.nodes.items()):
            if node.kind == "link" and node.target in _DEVICES:
                device = root / OUTSIDE / "dev" / node.target.rsplit("/", 1)[1]
                if not device.exists():
                    device.parent.mkdir(parents=True, exist_ok=True)
                    os.mknod(device, stat.S_IFCHR | 0o666, os.makedev(*_DEVICES[node.target]))
                tree.nodes[key] = type(node)("link", target=str(device))
    tree.materialise(root)
    (root / RUN).mkdir(exist_ok=True)


def run(
    invocation: Invocation,
    root: Path,
    tree: Tree,
    limits: Limits,
    *,
    kill_after: float | None = None,
) -> Outcome:
    """Run ``invocation`` in ``root/work`` (``tree`` gives its environment); wait, measure."""
    return finish(start(invocation, root, tree, limits), limits, kill_after=kill_after)


@dataclass(frozen=True)
class Started:
    pid: int
    started: float
    streams: Path


def start(
    invocation: Invocation, root: Path, tree: Tree, limits: Limits, streams: str = ""
) -> Started:
    """The run forked, not waited for; its streams in ``run/<streams>``."""
    folder = root / RUN / streams if streams else root / RUN
    folder.mkdir(parents=True, exist_ok=True)
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    started = time.monotonic()
    pid = os.fork()
    if pid == 0:  # pragma: no cover - the child
        code = 98
        try:
            code = _child(invocation, root, folder, tree, limits)
        except BaseException:
            with contextlib.suppress(Exception):
                traceback.print_exc()
        finally:
            os._exit(code)
    return Started(pid, started, folder)


def finish(
    run: Started, limits: Limits, *, kill_after: float | None = None, reap: bool = True
) -> Outcome:
    """
    Wait for ``run`` up to the time limit (or ``kill_after`` seconds: then SIGKILL it). ``reap``:
    then reap every orphan that came back to this process (not while another run is going).
    """
    timed_out = False
    wall = limits.seconds * limits.wall_factor
    left = run.started + (wall if kill_after is None else min(kill_after, wall)) - time.monotonic()
    if not _exited_within(run.pid, left):
        timed_out = kill_after is None or kill_after >= wall
        with contextlib.suppress(ProcessLookupError):
            os.killpg(run.pid, signal.SIGKILL)
    _, status, usage = os.wait4(run.pid, 0)
    seconds = time.monotonic() - run.started
    cpu_seconds = usage.ru_utime + usage.ru_stime
    # past the CPU limit, or stopped by the RLIMIT_CPU backstop (SIGXCPU, SIGKILL past it)
    if kill_after is None and (
        cpu_seconds > limits.seconds
        or (
            os.WIFSIGNALED(status)
            and os.WTERMSIG(status) in (signal.SIGXCPU, signal.SIGKILL)
            and cpu_seconds >= limits.seconds
        )
    ):
        timed_out = True
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(run.pid, signal.SIGKILL)  # what is left of its group: a forkserver, a sandbox
    if reap:
        reap_orphans()
    out, out_size = _read(run.streams / "stdout")
    err, err_size = _read(run.streams / "stderr")
    return Outcome(
        exit=os.WEXITSTATUS(status) if os.WIFEXITED(status) else None,
        signal=os.WTERMSIG(status) if os.WIFSIGNALED(status) else None,
        timed_out=timed_out,
        seconds=seconds,
        cpu_seconds=cpu_seconds,
        peak_mb=usage.ru_maxrss / 1024,
        stdout=out,
        stderr=err,
        stdout_size=out_size,
        stderr_size=err_size,
    )


def _exited_within(pid: int, seconds: float) -> bool:
    try:
        handle = os.pidfd_open(pid)
    except (AttributeError, OSError):
        handle = None
    if handle is not None:
        try:
            return bool(select.select([handle], [], [], max(seconds, 0))[0])
        finally:
            os.close(handle)
    end = time.monotonic() + seconds  # no pidfd: poll
    while time.monotonic() < end:
        if os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None:
            return True
        time.sleep(0.005)
    return False


def _read(path: Path) -> tuple[bytes, int]:
    try:
        size = path.stat().st_size
        with open(path, "rb") as stream:
            return stream.read(KEEP_BYTES), size
    except OSError:
        return b"", 0


# --- the child -------------------------------------------------------------------------------


def _child(invocation: Invocation, root: Path, streams: Path, tree: Tree, limits: Limits) -> int:
    os.setpgid(0, 0)
    import multiprocessing

    # a harness worker is a daemonic pool process; the command it runs is a process of its own,
    # which may start workers (-j)
    multiprocessing.current_process().daemon = False
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # a write past RLIMIT_FSIZE fails with EFBIG
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    page = os.sysconf("SC_PAGE_SIZE")
    with open("/proc/self/statm") as statm:
        address_space = int(statm.read().split()[0]) * page
    cap = address_space + (limits.address_space_mb << 20)
    resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
    resource.setrlimit(resource.RLIMIT_FSIZE, (limits.file_mb << 20, limits.file_mb << 20))
    cpu = int(limits.seconds) + 30  # a backstop should this process's parent die
    resource.setrlimit(resource.RLIMIT_CPU, (cpu, cpu))
    env = _environment(root, tree, limits)
    os.environ.clear()
    os.environ.update(env)
    _streams(root, streams, invocation.stdin)
    os.chdir(root / WORK)
    if AS_ROOT:
        drop_file_capabilities()
    if invocation.real:
        script = console_script(invocation.program)
        os.execve(script, [script, *invocation.args], env)
    return _in_process(invocation)


def _environment(root: Path, tree: Tree, limits: Limits) -> dict[str, str]:
    env = {
        k: v
        for k, v in os.environ.items()
        if not k.startswith(("INERTIA_KIT_", "ROS_", "AMENT_", "GITHUB_", "CI_", "PYTEST_"))
        and k not in ("FORCE_COLOR", "NO_COLOR", "COLUMNS", "XDG_CACHE_HOME")
    }
    env.update(
        INERTIA_KIT_CACHE_DIR=str(root / CACHE),
        INERTIA_KIT_TRACEBACK="1",  # an internal error prints where it happened
        HOME=str(root / HOME),
    )
    if limits.xacro_limits:
        env["INERTIA_KIT_XACRO_LIMITS"] = limits.xacro_limits
    env.update(tree.env)
    return env


def _streams(root: Path, folder: Path, stdin: str | None) -> None:
    try:
        source = os.open(root / WORK / stdin if stdin else os.devnull, os.O_RDONLY)
    except OSError:  # a shrunk input without the file: the command reads nothing
        source = os.open(os.devnull, os.O_RDONLY)
    os.dup2(source, 0)
    for fd, name in ((1, "stdout"), (2, "stderr")):
        target = os.open(folder / name, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
        os.dup2(target, fd)
        os.close(target)
    os.close(source)
    encoding = locale.getpreferredencoding(False)
    sys.stdin = io.TextIOWrapper(
        io.BufferedReader(io.FileIO(0, "r", closefd=False)), encoding=encoding
    )
    sys.stdout = io.TextIOWrapper(
        io.BufferedWriter(io.FileIO(1, "w", closefd=False)), encoding=encoding
    )
    sys.stderr = io.TextIOWrapper(
        io.BufferedWriter(io.FileIO(2, "w", closefd=False)),
        encoding=encoding,
        errors="backslashreplace",
        line_buffering=True,
    )


def _in_process(invocation: Invocation) -> int:
    from inertia_kit import cli

    command = {"inertia-lint": cli.lint_main, "inertia-fill": cli.fill_main}.get(
        invocation.program, cli.main
    )
    sys.argv = [invocation.program, *invocation.args]
    try:
        command.main(args=list(invocation.args), prog_name=invocation.program, standalone_mode=True)
        code = 0
    except SystemExit as leaving:
        code = leaving.code if isinstance(leaving.code, int) else (0 if leaving.code is None else 1)
        if not isinstance(leaving.code, int | None):
            print(leaving.code, file=sys.stderr)
    except BaseException:  # what would escape the console script: Python prints a traceback
        traceback.print_exc()
        code = 1
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(Exception):
            stream.flush()
    return code


def console_script(name: str) -> str:
    for folder in (sysconfig.get_path("scripts"), str(Path(sys.executable).parent)):
        path = Path(folder, name)
        if path.is_file():
            return str(path)
    raise FileNotFoundError(name)
