"""
Xacro expansion through the real ``xacro`` package, without ROS, with a source map.

:func:`expand` runs xacro in-process on files parsed by our own expat builder, which stamps every
element with its file, line and column (DOM user data, which minidom copies onto clones, so the
stamps survive macro expansion; see :mod:`.xacro_source_map`). Three xacro internals are
replaced for the duration of the call:

- ``xacro.parse``: files (the input and every include) are size-checked and refused if they
  declare entities, then parsed with the stamping builder;
- ``xacro.handle_macro_call``: elements a macro produced get the call site appended to their
  stamp's ``calls`` (outer calls are prepended later, so ``calls`` reads outermost first);
- ``xacro.substitution_args._eval_find``: ``$(find pkg)`` goes to a
  :class:`~inertia_kit.description.packages.PackageResolver` instead of ``ament_index_python``;
  ``xacro.eval_text`` is wrapped to see the path that follows it (``$(find pkg)/urdf/arm.xacro``),
  so that, as for a mesh, the candidate folder holding that path wins.

- ``xacro.safe_eval``: expressions run with ``**``, ``*`` and ``<<`` checked
  (:func:`~inertia_kit.description.xacro_limits.guarded_code`).

The expansion is bounded (:mod:`.xacro_limits`): it runs in a forked child process under a time
and a memory limit (:mod:`.xacro_sandbox`), which hands back the expanded tree as text with the
stamps; elements read and copied are counted against the element limit as they are made.

xacro keeps its state in module globals, so expansions are serialised by a lock; everything is
restored afterwards, also on error. What xacro prints to stderr from the expanding thread is
collected as :attr:`Expanded.warnings`. Errors become :class:`~inertia_kit.errors.InputError`
naming the file and line at fault (:mod:`.xacro_errors`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import os
import re
import sys
import threading
import time
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.dom import Node

from inertia_kit.description import safexml
from inertia_kit.description.model import Source
from inertia_kit.description.xacro_errors import PackageNotFound, input_error
from inertia_kit.description.xacro_limits import LimitExceeded, Meter, XacroLimits, guarded_code
from inertia_kit.description.xacro_sandbox import Expansion
from inertia_kit.description.xacro_source_map import (
    _COPY_STAMP,
    add_call_site,
    parse_stamped,
    serialise,
    stamp_of,
    to_lxml,
)
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.packages import PackageResolver

#: Top-level tags of a file meant to be included rather than expanded on its own.
FRAGMENT_TAGS = frozenset({"xacro:macro", "xacro:property", "xacro:arg", "xacro:include"})

_IS_XACRO = re.compile(rb"xmlns:xacro\s*=|<\s*xacro:[A-Za-z_]")
_LOCK = threading.Lock()


def is_xacro(data: bytes) -> bool:
    """Whether ``data`` is xacro by content: the xacro namespace declared or ``xacro:`` tags."""
    return _IS_XACRO.search(data) is not None


@dataclass(frozen=True)
class Expanded:
    """
    A xacro file expanded to a URDF element tree.

    Attributes
    ----------
    path : str
      The input file, as given.
    root : lxml.etree._Element
      The expanded robot, free of any stamp; an empty ``<robot>`` for a fragment.
    files : tuple of str
      Every file read, the input first, each once.
    fragment : bool
      The file holds only macros, properties, args and includes and produces no link or joint:
      it is meant to be included.
    warnings : tuple of str
      What xacro printed while expanding (``redefining global symbol: pi ...``).
    """

    path: str
    root: etree._Element
    files: tuple[str, ...]
    fragment: bool
    warnings: tuple[str, ...] = ()
    _sources: Mapping[Any, Source] = field(default_factory=dict, repr=False, compare=False)

    def source_of(self, element: etree._Element) -> Source:
        """
        Where ``element`` (of :attr:`root`) comes from.

        A macro-produced element has its location in the macro body and the macro calls that
        produced it in ``calls``, outermost first. An element without a stamp of its own
        (comments, anything xacro created) gets its nearest stamped ancestor's location.
        """
        node = element
        while node is not None:
            source = self._sources.get(node)
            if source is not None:
                return source
            node = node.getparent()
        return Source(self.path)


def expand(
    path: str | Path,
    *,
    args: Mapping[str, str] | None = None,
    resolver: PackageResolver | None = None,
    limits: XacroLimits | None = None,
) -> Expanded:
    """
    Expand a xacro file with the real ``xacro`` package, recording where each element came from.

    Parameters
    ----------
    path : str or Path
      The xacro file.
    args : mapping of str to str, optional
      Values for ``$(arg name)``, as ``name:=value`` on xacro's command line; ``xacro:arg``
      defaults fill in the rest.
    resolver : PackageResolver, optional
      Resolves ``$(find pkg)``; by default one that discovers packages near ``path``.
    limits : XacroLimits, optional
      Time, memory and element limits; by default :meth:`XacroLimits.resolve` (the defaults
      and ``INERTIA_KIT_XACRO_LIMITS``).

    Returns
    -------
    expanded : Expanded

    Raises
    ------
    InputError
      For anything xacro refuses (undefined property or argument, bad expression, missing
      include, unknown macro or package), an unreadable, oversized or malformed file, or one
      declaring entities; an expansion past a limit; naming the file (and line) at fault.
    """
    import xacro  # noqa: F401 - imported before any fork, once for every child

    from inertia_kit.description import xacro_sandbox
    from inertia_kit.description.packages import PackageResolver

    shown = str(path)
    if resolver is None:
        resolver = PackageResolver(start=path)
    if limits is None:
        limits = XacroLimits.resolve()
    start = time.monotonic()

    def work() -> Expansion:
        return _expand(shown, dict(args or {}), resolver, limits, start)

    def in_child() -> Expansion:
        # the packages the child looked up, for the parent's resolver (package:// next)
        return dataclasses.replace(work(), resolver_state=xacro_sandbox.state_of(resolver))

    result = None
    try:
        if (limits.timeout or limits.memory) and xacro_sandbox.can_fork():
            xacro_sandbox.preload()
            with contextlib.suppress(xacro_sandbox.CannotFork):
                result = xacro_sandbox.run(
                    in_child,
                    timeout=limits.timeout,
                    memory_mb=limits.memory,
                    start=start,
                    lock=_LOCK,
                )
        if result is None:  # no fork here, or none possible now: the in-process limits only
            with _LOCK:
                result = work()
    except xacro_sandbox.TimedOut:
        raise InputError(f"xacro: {limits.timed_out().told()}", shown) from None
    except (MemoryError, xacro_sandbox.ChildDied) as error:
        memory = limits.out_of_memory()
        if isinstance(error, xacro_sandbox.ChildDied):
            memory = LimitExceeded(f"{memory} ({error.reason()})", memory.hint)
        raise InputError(f"xacro: {memory.told()}", shown) from None
    if result.resolver_state:
        vars(resolver).update(result.resolver_state)
    return _expanded(result)


def _expanded(result: Expansion) -> Expanded:
    """The expansion handed over (from the child) as the lxml tree and its source map."""
    from lxml import etree

    if result.text is None or result.sources is None:
        return Expanded(result.path, etree.Element("robot"), result.files, True, result.warnings)
    root, sources = to_lxml(result.text, result.sources, Source(result.path))
    if result.maybe_fragment and not any(child.tag in ("link", "joint") for child in root):
        return Expanded(result.path, etree.Element("robot"), result.files, True, result.warnings)
    return Expanded(result.path, root, result.files, False, result.warnings, sources)


def _expand(
    shown: str, args: dict[str, str], resolver: PackageResolver, limits: XacroLimits, start: float
) -> Expansion:
    """The expansion itself (in the child process, or in-process under ``_LOCK``)."""
    import xacro

    session = _Session(shown, resolver, Meter(limits, start))
    with _patched(xacro, session):
        try:
            doc = session.parse_file(shown)
        except OSError as error:
            raise InputError(f"cannot read: {error.strerror or error}", shown) from None
        except LimitExceeded as error:
            raise InputError(f"xacro: {error.told()}", shown) from None
        top = {
            child.tagName
            for child in doc.documentElement.childNodes
            if child.nodeType == Node.ELEMENT_NODE
        }
        if top <= FRAGMENT_TAGS - {"xacro:include"}:
            # Nothing here can produce a link or joint; expanding could only fail on context
            # that the including file provides.
            return session.result(None)
        try:
            xacro.init_stacks(shown)
            xacro.process_doc(doc, mappings=args, verbosity=1)
        except InputError:
            raise
        except Exception as error:  # xacro raises anything from NameError to RuntimeError
            raise input_error(
                error, session.path, session.display, limits.out_of_memory()
            ) from None
        return session.result(doc.documentElement, maybe_fragment=top <= FRAGMENT_TAGS)


# --- one expansion --------------------------------------------------------------------------


class _Session:
    """The state of one expansion: files read, captured output, and the hooks' bodies."""

    def __init__(self, path: str, resolver: PackageResolver, meter: Meter | None = None):
        self.path = path
        self.resolver = resolver
        self.meter = meter if meter is not None else Meter(XacroLimits(0, 0, 0))
        self.builtins = self.meter.builtins()
        self.files: list[str] = []
        self.stderr = io.StringIO()
        self.includes_start = 0
        self.texts: list[str] = []  # the texts xacro is evaluating, innermost last

    # --- hooks ------------------------------------------------------------------------------

    def parse_file(self, filename: str):
        """Read ``filename`` safely and parse it with stamps (minidom ``Document``)."""
        import xacro

        shown = self.display(filename) if self.files else filename
        data = _read_checked(os.path.join(xacro.root_dir, filename), shown)
        if shown not in self.files:
            self.files.append(shown)
        return parse_stamped(data, shown, self.meter.add)

    def display(self, filename: str) -> str:
        """How to show an included file: relative to the working folder if the input is."""
        shown = os.path.normpath(filename)
        if os.path.isabs(shown) and not os.path.isabs(self.path):
            relative = os.path.relpath(shown)
            if not relative.startswith(os.pardir):
                return relative
        return shown

    def parse(self, inp, filename=None):
        """Replaces ``xacro.parse``: same contract, safe and stamping."""
        import xacro

        if inp is None:
            try:
                return self.parse_file(filename)
            except OSError as error:
                # as xacro does: the failing file is not "the file being processed"
                xacro.filestack.pop()
                reason = error.strerror or str(error)
                raise xacro.XacroException(f"{reason}: {filename}", exc=error) from None
        shown = (xacro.filestack or [None])[-1] or "<string>"
        if hasattr(inp, "read"):
            inp = inp.read(safexml.MAX_BYTES + 1)
        if isinstance(inp, str):
            inp = inp.encode("utf-8")
        if isinstance(inp, bytes):
            _check_bytes(inp, shown)
            return parse_stamped(inp, shown, self.meter.add)
        return inp

    def handle_macro_call(self, original):
        def hook(node, macros, symbols):
            # xacro:call renames itself and re-enters this hook: stamp only once.
            if node.tagName == "xacro:call" or not node.tagName.startswith("xacro:"):
                return original(node, macros, symbols)
            call = stamp_of(node)
            parent = node.parentNode
            before = set(parent.childNodes)
            handled = original(node, macros, symbols)
            if handled and call is not None:
                site = Source(call.path, call.line, call.column)
                for child in parent.childNodes:
                    if child.nodeType == Node.ELEMENT_NODE and child not in before:
                        add_call_site(child, site)
            return handled

        return hook

    def eval_text(self, original):
        def hook(text, symbols):
            self.texts.append(text)
            try:
                return original(text, symbols)
            finally:
                self.texts.pop()

        return hook

    def safe_eval(self, expr, globals, locals=None):
        """Replaces ``xacro.safe_eval``: the same, with ``**``, ``*`` and ``<<`` checked."""
        code = guarded_code(expr.strip())
        self.meter.check_time()
        globals.update(__builtins__=self.builtins)  # xacro's, plus the checked operators
        return eval(code, globals, locals)

    def find(self, package: str) -> str:
        """Replaces ``substitution_args._eval_find``."""
        import xacro

        near = (xacro.filestack or [None])[-1] or self.path
        rest = _path_after_find(package, self.texts)
        folder = self.resolver.find(package, near, rest)
        if folder is None and near != self.path:
            folder = self.resolver.find(package, self.path, rest)
        if folder is None:
            places = self.resolver.lookup(package, near).places
            raise PackageNotFound(package, str(Path(near).parent), tuple(map(str, places)))
        # absolute, as ROS gives it: xacro joins a relative include to the including file's folder
        return str(folder.absolute())

    # --- results ----------------------------------------------------------------------------

    def warnings(self) -> tuple[str, ...]:
        entries: list[list[str]] = []
        for line in self.stderr.getvalue().splitlines():
            line = line.strip()
            if not line:
                continue
            for prefix in ("warning: ", "error: "):
                if line.startswith(prefix):
                    entries.append([line[len(prefix) :]])
                    break
            else:
                if entries:
                    entries[-1].append(line)
                else:
                    entries.append([line])
        return tuple(
            first if not rest else f"{first} ({'; '.join(rest)})" for first, *rest in entries
        )

    def result(self, root, *, maybe_fragment: bool = False) -> Expansion:
        """What the expansion gives: the robot ``root`` (``None``: a fragment) serialised."""
        import xacro

        files = list(self.files)
        for name in xacro.all_includes[self.includes_start :]:
            shown = self.display(name)
            if shown not in files and os.path.isfile(name):
                files.append(shown)
        if root is None:
            return Expansion(self.path, tuple(files), True, self.warnings())
        text, sources = serialise(root, Source(self.path))
        return Expansion(
            self.path, tuple(files), False, self.warnings(), text, sources, maybe_fragment
        )


@contextlib.contextmanager
def _patched(xacro, session: _Session, stamping: bool = True) -> Iterator[None]:
    """Install the hooks (the caller holds ``_LOCK``) and restore xacro exactly afterwards."""
    from xacro import substitution_args

    patches: list[tuple[Any, str, Any]] = [
        (substitution_args, "_eval_find", session.find),
        (xacro, "eval_text", session.eval_text(xacro.eval_text)),
    ]
    if stamping:
        patches += [
            (xacro, "parse", session.parse),
            (xacro, "handle_macro_call", session.handle_macro_call(xacro.handle_macro_call)),
            (xacro, "safe_eval", session.safe_eval),
            (_COPY_STAMP, "on_copy", session.meter.add),
        ]
    saved = [(owner, name, getattr(owner, name)) for owner, name, _ in patches]
    saved_find = substitution_args._eval_dict.get("find")
    saved_state = (
        xacro.filestack,
        xacro.macrostack,
        xacro.verbosity,
        dict(xacro.substitution_args_context),
    )
    session.includes_start = len(xacro.all_includes)
    stderr = sys.stderr
    sys.stderr = _ThreadRoutedStream(stderr, session.stderr)
    try:
        for owner, name, value in patches:
            setattr(owner, name, value)
        substitution_args._eval_dict["find"] = session.find
        yield
    finally:
        sys.stderr = stderr
        for owner, name, value in saved:
            setattr(owner, name, value)
        substitution_args._eval_dict["find"] = saved_find
        xacro.filestack, xacro.macrostack, xacro.verbosity, context = saved_state
        xacro.substitution_args_context.clear()
        xacro.substitution_args_context.update(context)
        # xacro never empties this list: keep it from growing with every expansion.
        del xacro.all_includes[session.includes_start :]


class _ThreadRoutedStream:
    """``sys.stderr`` while xacro runs: the expanding thread's writes go to ``sink``."""

    def __init__(self, stream, sink: io.StringIO):
        self._stream = stream
        self._sink = sink
        self._owner = threading.get_ident()

    def _target(self):
        return self._sink if threading.get_ident() == self._owner else self._stream

    def write(self, text: str) -> int:
        return self._target().write(text)

    def flush(self) -> None:
        self._target().flush()

    def isatty(self) -> bool:
        return self._target().isatty()

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


def _path_after_find(package: str, texts: list[str]) -> str:
    """The path written right after ``$(find package)`` in the innermost text holding it."""
    pattern = re.compile(r"\$\(find\s+" + re.escape(package) + r"\s*\)([^\s\"'$()<>]*)")
    for text in reversed(texts):
        match = pattern.search(text) if isinstance(text, str) else None
        if match:
            return match.group(1)
    return ""


# --- reading and parsing --------------------------------------------------------------------


def _read_checked(filename: str, shown: str) -> bytes:
    """The bytes of ``filename``, refused (``InputError``) when too large or declaring entities."""
    # an OSError propagates: xacro reports a missing include at the line that includes it
    with open(filename, "rb") as stream:
        data = stream.read(safexml.MAX_BYTES + 1)
    _check_bytes(data, shown)
    return data


def _check_bytes(data: bytes, shown: str) -> None:
    safexml.check_size(data, shown)
    safexml.refuse_entities(data, shown)
