"""
What a run must never do, as :class:`Failure` s of a class (``kind``) and a signature
(``detail``): the summary counts them by both, the shrinker keeps a smaller input only while
it fails with the same signature, and the CI test excuses only the signatures of known-open
classes (fuzz.known).

- ``internal-error`` (by exception type and the deepest frame in inertia_kit), ``traceback``
  (one that escaped the guard), ``crash`` (a signal), ``exit-code`` (outside 0, 1, 2, 130);
- ``timeout`` (over the time limit), ``memory`` (peak resident memory over the limit, or a
  ``MemoryError`` under the harness's address-space cap), ``huge-output`` (a file or stream past
  the harness's size cap);
- ``changed-input`` (a command that writes no robot changed a file of the repository),
  ``write-outside`` (a file outside the repository changed or appeared), ``stray-file`` (a file
  left behind), ``mode-changed``;
- ``unparsable-write`` (a robot that parsed no longer does), ``not-idempotent`` (a second run
  changed the file again), ``unparsable-output`` (JSON, SARIF, JUnit, ``-o`` outputs);
- ``injection`` (a raw control character in a line of text output, or a line starting with the
  canary a hostile name or file name carries after its line break);
- ``interrupted-partial`` (a SIGKILLed writer left a file that is neither the old one nor the
  new one), ``concurrent-state`` (two writers at once ended in a state no sequential order gives).
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from pathlib import PurePosixPath

from lxml import etree

from fuzz.execute import KEEP_BYTES, RUN, Limits, Outcome
from fuzz.mutate import CANARY
from fuzz.plan import Invocation
from fuzz.tree import CACHE, HOME, OUTSIDE, WORK, Seen, changes

ROBOT_SUFFIXES = (".urdf", ".xacro", ".xml")
#: what a killed run may leave: a write's temporary file, the stand-in of a robot read from stdin
TEMPORARY = re.compile(r"\..+\.inertia-kit-[0-9a-f]{12}\.tmp$|^\.inertia-kit-stdin-")
EXITS = (0, 1, 2, 130)
HUGE_OUTPUT = 256 << 20


@dataclass(frozen=True)
class Failure:
    kind: str
    detail: str
    message: str

    @property
    def signature(self) -> str:
        return f"{self.kind}: {self.detail}"


def label(invocation: Invocation) -> str:
    """The command a failure is told by: the program and what the run covers first."""
    return invocation.covers[0] if invocation.covers else invocation.program


# --- one run's outcome -----------------------------------------------------------------------

_FRAME = re.compile(r'^\s*File "([^"]+)", line (\d+), in (\S+)', re.M)
_EXCEPTION = re.compile(
    r"^([A-Za-z_][\w.]*(?:Error|Exception|Exit|Interrupt|Warning|Iteration)\w*)(?::|$)", re.M
)


def _traceback_place(text: str) -> tuple[str, str] | None:
    """(exception type, deepest inertia_kit frame) of the last traceback in ``text``."""
    start = text.rfind("Traceback (most recent call last):")
    if start < 0:
        return None
    block = text[start:]
    frames = _FRAME.findall(block)
    ours = [f for f in frames if "/inertia_kit/" in f[0]]
    where = ours[-1] if ours else (frames[-1] if frames else None)
    place = "?"
    if where is not None:
        path = (
            where[0].split("/inertia_kit/", 1)[-1]
            if "/inertia_kit/" in where[0]
            else where[0].rsplit("/", 1)[-1]
        )
        place = f"{path}:{where[2]}"
    exceptions = [m.group(1) for m in _EXCEPTION.finditer(block)]
    return (exceptions[-1] if exceptions else "?"), place


_INTERNAL = re.compile(r"internal error: ([A-Za-z_][\w.]*)")


def check_outcome(invocation: Invocation, outcome: Outcome, limits: Limits) -> list[Failure]:
    found: list[Failure] = []
    command = label(invocation)
    err = outcome.stderr.decode("utf-8", "replace")
    out = outcome.stdout.decode("utf-8", "replace")
    if outcome.timed_out:
        spent = f"{outcome.cpu_seconds:.0f} s CPU, {outcome.seconds:.0f} s wall"
        return [Failure("timeout", command, f"over {limits.seconds:g} s of CPU ({spent})")]
    if outcome.peak_mb > limits.memory_mb:
        found.append(Failure("memory", command, f"peak {outcome.peak_mb:.0f} MB"))
    if outcome.signal is not None:
        found.append(
            Failure(
                "crash", f"{command} signal {outcome.signal}", f"killed by signal {outcome.signal}"
            )
        )
    elif outcome.exit not in EXITS:
        found.append(Failure("exit-code", f"{command} exit {outcome.exit}", f"exit {outcome.exit}"))
    internal = _INTERNAL.search(err) or _INTERNAL.search(out)
    place = _traceback_place(err)
    if internal is not None:
        kind = place[0] if place else internal.group(1)
        where = place[1] if place else "?"
        line = next((x for x in err.splitlines() if "internal error" in x), internal.group(0))
        cls = "memory" if kind == "MemoryError" else "internal-error"
        if "[Errno 27]" in line:  # EFBIG: a write past the harness's RLIMIT_FSIZE
            cls, kind, where = "huge-output", label(invocation), "the file size limit"
        found.append(Failure(cls, f"{kind} at {where}", line[:300]))
    elif place is not None:
        found.append(Failure("traceback", f"{place[0]} at {place[1]}", err[-300:]))
    if "File too large" in err or max(outcome.stdout_size, outcome.stderr_size) > HUGE_OUTPUT:
        found.append(
            Failure(
                "huge-output",
                command,
                f"stdout {outcome.stdout_size} B, stderr {outcome.stderr_size} B",
            )
        )
    found += check_streams(invocation, outcome, out, err)
    return found


#: a raw control character (tab and newline are text), DEL, C1 (NEL included), U+2028/2029
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u2028\u2029]")


def _injected(text: str, *, controls: bool) -> str | None:
    """What in ``text`` could start a line of its own or drive a terminal, or None."""
    if controls:
        found = _CONTROL.search(text)
        if found is not None:
            return f"raw U+{ord(found.group(0)):04X}"
    for line in text.split("\n"):
        if line.lstrip().startswith(CANARY):
            return "a line break before a name"
    return None


def check_streams(invocation: Invocation, outcome: Outcome, out: str, err: str) -> list[Failure]:
    found = []
    command = label(invocation)
    # stderr is text for every command; stdout is text for the text formats
    what = _injected(err, controls=True)
    if what is not None:
        found.append(Failure("injection", f"{command} stderr: {what}", _context(err, what)))
    kind = invocation.stdout_kind
    if kind in ("text", "markdown", "diff"):
        what = _injected(out, controls=kind != "diff")  # a diff shows the file's own bytes
        if what is not None:
            found.append(Failure("injection", f"{command} stdout: {what}", _context(out, what)))
    if outcome.stdout_size <= KEEP_BYTES and out.strip():
        problem = _unparsable(outcome.stdout, kind)
        if problem:
            found.append(Failure("unparsable-output", f"{command} stdout", problem))
    return found


def _context(text: str, what: str) -> str:
    found = _CONTROL.search(text) if what.startswith("raw") else re.search(re.escape(CANARY), text)
    at = found.start() if found else 0
    return f"{what}: …{text[max(0, at - 80) : at + 40]!r}…"


def _unparsable(data: bytes, kind: str | None) -> str | None:
    try:
        if kind == "json":
            json.loads(data)
        elif kind == "xml":
            parse_xml(data)
        elif kind == "html" and b"</html>" not in data[-4096:]:
            return "no </html> at the end"
    except (ValueError, etree.XMLSyntaxError) as error:
        return f"{type(error).__name__}: {str(error)[:200]}"
    return None


_PARSER = etree.XMLParser(resolve_entities=False, no_network=True, load_dtd=False, huge_tree=True)


def parse_xml(data: bytes):
    return etree.fromstring(data, _PARSER)


def parses(data: bytes | None) -> bool:
    if data is None:
        return False
    try:
        parse_xml(data)
        return True
    except (etree.XMLSyntaxError, ValueError):
        return False


# --- the tree ------------------------------------------------------------------------------------


def is_robot(key: str) -> bool:
    return key.startswith(WORK + "/") and PurePosixPath(key).suffix.lower() in ROBOT_SUFFIXES


def check_tree(
    invocation: Invocation, before: dict[str, Seen], after: dict[str, Seen], *, killed: bool = False
) -> tuple[list[Failure], list[str]]:
    """
    The failures in what the run did to the folder, and the robot files it edited (a writer
    may edit robot files in place; ``killed``: a SIGKILLed run may leave its temporary file).
    """
    found, edited = [], []
    # told by what writes (-o, a writer, or neither), not by the output format: one bug, one
    # signature
    command = f"{invocation.program} -o" if invocation.output else label(invocation)
    if not invocation.output and invocation.program == "inertia-lint" and not invocation.writes:
        command = "inertia-lint"
    for key, how in sorted(changes(before, after).items()):
        top = key.split("/", 1)[0]
        if top in (CACHE, HOME, RUN) or key in (CACHE, HOME, RUN):
            continue
        if top != WORK:
            found.append(Failure("write-outside", f"{command} {how} {_shape(key)}", f"{how} {key}"))
            continue
        relative = key[len(WORK) + 1 :]
        if invocation.output and relative == invocation.output:
            continue
        if how == "created" and TEMPORARY.search(PurePosixPath(key).name):
            if not killed:
                kind = "stand-in" if "-stdin-" in key else "temporary file"
                found.append(Failure("stray-file", f"{command} {kind}", f"left {key}"))
            continue
        was, now = before.get(key), after.get(key)
        if (
            invocation.writes
            and how == "changed"
            and was
            and now
            and was.kind == now.kind == "file"
            and is_robot(key)
        ):
            edited.append(key)
            if was.mode != now.mode:
                found.append(
                    Failure("mode-changed", command, f"{key}: {oct(was.mode)} -> {oct(now.mode)}")
                )
            continue
        if how == "created":
            found.append(Failure("stray-file", f"{command} {_shape(key)}", f"created {key}"))
        else:
            found.append(Failure("changed-input", f"{command} {how} {_shape(key)}", f"{how} {key}"))
    return found, edited


def _shape(key: str) -> str:
    """A path told by what it is, not by its name: the same bug has one signature."""
    path = PurePosixPath(key)
    if path.parts[0] == OUTSIDE:
        return key
    return (
        f"*{path.suffix.lower()}"
        if path.suffix
        else path.name
        if path.name.startswith(".")
        else "file"
    )
