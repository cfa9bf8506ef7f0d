"""
One xacro expansion's state and the hooks it installs in the ``xacro`` package, for
:mod:`.xacro_expand` (whose docstring lists what each hook replaces).

:class:`Session` holds what one expansion reads and prints (files, captured stderr, the texts
being evaluated) and the hooks' bodies: the safe, stamping ``parse``, the call-site stamps of
``handle_macro_call``, the checked ``safe_eval`` and ``$(find)`` through a
:class:`~inertia_kit.description.urdf.packages.PackageResolver`; ``$(env)``, ``$(optenv)`` and
``xacro.load_yaml`` record what the environment gives (:mod:`.redaction`). :func:`patched`
installs them (the caller holds the expansion lock) and restores xacro's globals exactly
afterwards, also on error.
Files are read size-checked and refused if they declare entities (:func:`read_checked`).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.dom import Node

from inertia_kit.description import reads, safexml
from inertia_kit.description.model import Source
from inertia_kit.description.urdf import xacro_dom, xacro_yaml
from inertia_kit.description.urdf.xacro_errors import PackageNotFound
from inertia_kit.description.urdf.xacro_sandbox import Expansion
from inertia_kit.description.urdf.xacro_source_map import (
    _COPY_STAMP,
    add_call_site,
    parse_stamped,
    serialise,
    stamp_of,
)
from inertia_kit.description.xacro_limits import Meter, XacroLimits, guarded_code
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from inertia_kit.description.urdf.packages import PackageResolver


class Session:
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
        # what the environment gave: $(env), $(optenv) and YAML values (description.redaction)
        self.environment_values: dict[str, None] = {}
        self.reads: dict[str, str | None] = {}  # every file read: description.reads
        self.calls: dict[Any, Source] = {}  # macro call node -> its site, while it expands

    # --- hooks ------------------------------------------------------------------------------

    def parse_file(self, filename: str):
        """Read ``filename`` safely and parse it with stamps (minidom ``Document``)."""
        import xacro

        shown = self.display(filename) if self.files else filename
        data = read_checked(os.path.join(xacro.root_dir, filename), shown)
        reads.record(self.reads, os.path.join(xacro.root_dir, filename), data)
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
            check_bytes(inp, shown)
            return parse_stamped(inp, shown, self.meter.add)
        return inp

    def handle_macro_call(self, original):
        def hook(node, macros, symbols):
            # xacro:call renames itself and re-enters this hook: stamp only once.
            if node.tagName == "xacro:call" or not node.tagName.startswith("xacro:"):
                return original(node, macros, symbols)
            call = stamp_of(node)
            if call is not None:  # stamped as the expansion replaces the call (replace_node)
                self.calls[node] = Source(call.path, call.line, call.column)
            try:
                return original(node, macros, symbols)
            finally:
                self.calls.pop(node, None)

        return hook

    def replace_node(self, original):
        def hook(node, by, content_only=False):
            # a macro call's expansion: its elements carry the call site. Taken from the
            # expansion itself, not by comparing the parent's children before and after (as
            # many as the robot's links, for each call: quadratic)
            site = self.calls.pop(node, None)
            if site is not None and by is not None:
                for part in by if isinstance(by, list) else [by]:
                    for child in part.childNodes if content_only else [part]:
                        if child.nodeType == Node.ELEMENT_NODE:
                            add_call_site(child, site)
            return original(node, by, content_only)

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

    def reads_environment(self, original):
        """``$(env)`` and ``$(optenv)``: the value, recorded when it is the environment's."""

        def hook(name, *args, **kwargs):
            value = original(name, *args, **kwargs)
            if name in os.environ:
                self.record(value)
            return value

        return hook

    def loads_yaml(self, original):
        """``xacro.load_yaml``: what it loads, its scalar values recorded."""

        def hook(*args, **kwargs):
            loaded = original(*args, **kwargs)
            self.record_yaml(loaded)
            return loaded

        return hook

    def record_yaml(self, loaded: Any) -> None:
        # each node once (anchors share them, and may make cycles); keys are names, not values
        seen: set[int] = set()
        stack = [loaded]
        while stack:
            node = stack.pop()
            if isinstance(node, dict | list):
                if id(node) not in seen:
                    seen.add(id(node))
                    stack.extend(dict.values(node) if isinstance(node, dict) else node)
            else:
                self.record(node)

    def record(self, value: Any) -> None:
        from inertia_kit.description.redaction import recordable

        text = recordable(value)
        if text is not None:
            self.environment_values[text] = None

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

    def result(self, root) -> Expansion:
        """What the expansion gives: the robot ``root`` (``None``: a fragment) serialised."""
        import xacro

        files = list(self.files)
        for name in xacro.all_includes[self.includes_start :]:
            shown = self.display(name)
            if shown not in files and os.path.isfile(name):
                files.append(shown)
        environment = tuple(self.environment_values)
        if root is None:
            return Expansion(
                self.path,
                tuple(files),
                True,
                self.warnings(),
                environment_values=environment,
                reads=self.reads,
            )
        text, sources = serialise(root, Source(self.path))
        return Expansion(
            self.path,
            tuple(files),
            False,
            self.warnings(),
            text,
            sources,
            None,
            environment,
            self.reads,
        )


@contextlib.contextmanager
def patched(xacro, session: Session, stamping: bool = True) -> Iterator[None]:
    """Install the hooks (the caller holds the lock) and restore xacro exactly afterwards."""
    from xacro import substitution_args

    patches: list[tuple[Any, str, Any]] = [
        (substitution_args, "_eval_find", session.find),
        (xacro, "eval_text", session.eval_text(xacro.eval_text)),
    ]
    entries: list[tuple[dict, str, Any]] = [(substitution_args._eval_dict, "find", session.find)]
    if stamping:
        patches += [
            (xacro, "parse", session.parse),
            (xacro, "handle_macro_call", session.handle_macro_call(xacro.handle_macro_call)),
            (xacro, "replace_node", session.replace_node(xacro_dom.replace_node)),
            (xacro, "remove_previous_comments", xacro_dom.remove_previous_comments),
            (xacro, "safe_eval", session.safe_eval),
            (_COPY_STAMP, "on_copy", session.meter.add),
        ]
    patches += [  # $(env) and $(optenv), recorded
        (substitution_args, name, session.reads_environment(getattr(substitution_args, name)))
        for name in ("_eval_env", "_eval_optenv")
    ]
    saved = [(owner, name, getattr(owner, name)) for owner, name, _ in patches]
    saved_entries = [(owner, key, owner.get(key)) for owner, key, _ in entries]
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
        for owner, key, value in entries:
            owner[key] = value
        with xacro_yaml.hooked(xacro, session.meter), _recording_yaml(xacro, session):
            yield  # YAML bounded as the rest of the expansion, and what it gives recorded
    except InputError as error:  # its message may quote them
        error.environment_values = tuple(session.environment_values)
        raise
    finally:
        sys.stderr = stderr
        xacro_dom.forget()
        for owner, name, value in saved:
            setattr(owner, name, value)
        for owner, key, value in saved_entries:
            owner[key] = value
        xacro.filestack, xacro.macrostack, xacro.verbosity, context = saved_state
        xacro.substitution_args_context.clear()
        xacro.substitution_args_context.update(context)
        # xacro never empties this list: keep it from growing with every expansion.
        del xacro.all_includes[session.includes_start :]


@contextlib.contextmanager
def _recording_yaml(xacro, session: Session) -> Iterator[None]:
    """``xacro.load_yaml`` (and its deprecated top-level name) in ``${...}``'s symbols wrapped,
    while the expansion runs, by a hook recording what it loads; restored afterwards. Entered
    after :func:`.xacro_yaml.hooked`, so that it records what the bounded loader gives."""
    symbols = getattr(xacro, "_global_symbols", {})
    tables = [
        table
        for table in (symbols.get("xacro"), symbols)
        if isinstance(table, dict) and callable(table.get("load_yaml"))
    ]
    saved = [(table, table["load_yaml"]) for table in tables]
    try:
        for table, loader in saved:
            # dict's own: xacro's tables warn of a redefined global symbol
            dict.__setitem__(table, "load_yaml", session.loads_yaml(loader))
        yield
    finally:
        for table, loader in saved:
            dict.__setitem__(table, "load_yaml", loader)


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


def read_checked(filename: str, shown: str) -> bytes:
    """The bytes of ``filename``, refused (``InputError``) when too large or declaring entities."""
    # an OSError propagates: xacro reports a missing include at the line that includes it
    os.stat(filename)
    data = safexml.read_bounded(filename, shown)  # a regular file only: no pipe, no device
    check_bytes(data, shown)
    return data


def check_bytes(data: bytes, shown: str) -> None:
    safexml.check_size(data, shown)
    safexml.refuse_entities(data, shown)
