"""
Xacro expansion through the real ``xacro`` package, without ROS, with a source map.

:func:`expand` runs xacro in-process on files parsed by our own expat builder, which stamps every
element with its file, line and column (DOM user data, which minidom copies onto clones, so the
stamps survive macro expansion). Three xacro internals are replaced for the duration of the call:

- ``xacro.parse``: files (the input and every include) are size-checked and refused if they
  declare entities, then parsed with the stamping builder;
- ``xacro.handle_macro_call``: elements a macro produced get the call site appended to their
  stamp's ``calls`` (outer calls are prepended later, so ``calls`` reads outermost first);
- ``xacro.substitution_args._eval_find``: ``$(find pkg)`` goes to a
  :class:`~inertia_kit.description.packages.PackageResolver` instead of ``ament_index_python``.

xacro keeps its state in module globals, so expansions are serialised by a lock; everything is
restored afterwards, also on error. What xacro prints to stderr from the expanding thread is
collected as :attr:`Expanded.warnings`. Errors become :class:`~inertia_kit.errors.InputError`
naming the file and line at fault.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import os
import re
import sys
import threading
import traceback
from collections.abc import Iterator, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.dom import Node, UserDataHandler

from inertia_kit.description import safexml
from inertia_kit.description.model import Source
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.packages import PackageResolver

#: Top-level tags of a file meant to be included rather than expanded on its own.
FRAGMENT_TAGS = frozenset({"xacro:macro", "xacro:property", "xacro:arg", "xacro:include"})

_STAMP = "inertia_kit.source"
_IS_XACRO = re.compile(rb"xmlns:xacro\s*=|<\s*xacro:[A-Za-z_]")
_LOCK = threading.Lock()
_PACKAGE_HINT = "pass --package-path DIR with the package folder or a folder that holds it"


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

    Returns
    -------
    expanded : Expanded

    Raises
    ------
    InputError
      For anything xacro refuses (undefined property or argument, bad expression, missing
      include, unknown macro or package), an unreadable, oversized or malformed file, or one
      declaring entities; naming the file (and line) at fault.
    """
    import xacro

    from inertia_kit.description.packages import PackageResolver

    shown = str(path)
    if resolver is None:
        resolver = PackageResolver(start=path)
    session = _Session(shown, resolver)
    with _LOCK, _patched(xacro, session):
        try:
            doc = session.parse_file(shown)
        except OSError as error:
            raise InputError(f"cannot read: {error.strerror or error}", shown) from None
        top = {
            child.tagName
            for child in doc.documentElement.childNodes
            if child.nodeType == Node.ELEMENT_NODE
        }
        if top <= FRAGMENT_TAGS - {"xacro:include"}:
            # Nothing here can produce a link or joint; expanding could only fail on context
            # that the including file provides.
            return session.result(None, fragment=True)
        try:
            xacro.init_stacks(shown)
            xacro.process_doc(doc, mappings=dict(args or {}), verbosity=1)
        except InputError:
            raise
        except Exception as error:  # xacro raises anything from NameError to RuntimeError
            raise session.input_error(error) from None
        expanded = session.result(doc.documentElement, fragment=False)
        if top <= FRAGMENT_TAGS and not any(
            child.tag in ("link", "joint") for child in expanded.root
        ):
            return session.result(None, fragment=True)
        return expanded


# --- one expansion --------------------------------------------------------------------------


class _PackageNotFound(LookupError):
    def __init__(self, package: str, near: str):
        self.package = package
        super().__init__(
            f"package `{package}` not found for $(find {package}) (searched --package-path, "
            f"ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and the folders above {near}): {_PACKAGE_HINT}"
        )


class _CopyStampOnClone:
    """A DOM ``UserDataHandler``: a clone of a stamped node (a macro body) keeps its stamp."""

    def handle(self, operation, key, data, src, dst) -> None:
        if dst is not None and operation in (
            UserDataHandler.NODE_CLONED,
            UserDataHandler.NODE_IMPORTED,
        ):
            dst.setUserData(key, data, self)


_COPY_STAMP = _CopyStampOnClone()


class _Session:
    """The state of one expansion: files read, captured output, and the hooks' bodies."""

    def __init__(self, path: str, resolver: PackageResolver):
        self.path = path
        self.resolver = resolver
        self.files: list[str] = []
        self.stderr = io.StringIO()
        self.includes_start = 0

    # --- hooks ------------------------------------------------------------------------------

    def parse_file(self, filename: str):
        """Read ``filename`` safely and parse it with stamps (minidom ``Document``)."""
        import xacro

        shown = self.display(filename) if self.files else filename
        data = _read_checked(os.path.join(xacro.root_dir, filename), shown)
        if shown not in self.files:
            self.files.append(shown)
        return _parse_stamped(data, shown)

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
            return _parse_stamped(inp, shown)
        return inp

    def handle_macro_call(self, original):
        def hook(node, macros, symbols):
            # xacro:call renames itself and re-enters this hook: stamp only once.
            if node.tagName == "xacro:call" or not node.tagName.startswith("xacro:"):
                return original(node, macros, symbols)
            call = node.getUserData(_STAMP)
            parent = node.parentNode
            before = set(parent.childNodes)
            handled = original(node, macros, symbols)
            if handled and call is not None:
                site = Source(call.path, call.line, call.column)
                for child in parent.childNodes:
                    if child.nodeType == Node.ELEMENT_NODE and child not in before:
                        for element in _elements(child):
                            source = element.getUserData(_STAMP)
                            if source is not None:
                                calls = (site, *source.calls)
                                stamp = dataclasses.replace(source, calls=calls)
                                element.setUserData(_STAMP, stamp, _COPY_STAMP)
            return handled

        return hook

    def find(self, package: str) -> str:
        """Replaces ``substitution_args._eval_find``."""
        import xacro

        near = (xacro.filestack or [None])[-1] or self.path
        folder = self.resolver.find(package, near)
        if folder is None and near != self.path:
            folder = self.resolver.find(package, self.path)
        if folder is None:
            raise _PackageNotFound(package, str(Path(near).parent))
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

    def result(self, root, *, fragment: bool) -> Expanded:
        import xacro
        from lxml import etree

        files = list(self.files)
        for name in xacro.all_includes[self.includes_start :]:
            shown = self.display(name)
            if shown not in files and os.path.isfile(name):
                files.append(shown)
        if root is None:
            return Expanded(
                self.path, etree.Element("robot"), tuple(files), fragment, self.warnings()
            )
        lxml_root, sources = _to_lxml(root, Source(self.path))
        return Expanded(self.path, lxml_root, tuple(files), fragment, self.warnings(), sources)

    def input_error(self, error: BaseException) -> InputError:
        """An :class:`InputError` for what xacro raised, at the innermost element it was on."""
        import xacro

        not_found = _cause(error, _PackageNotFound)
        node, macro_calls = _fault_site(error, xacro.__file__)
        source = _source_near(node)
        if source is None:
            stack = [f for f in (xacro.filestack or []) if f]
            source = Source(self.display(stack[-1]) if len(stack) > 1 else self.path)
        message = str(not_found) if not_found is not None else _message(error)
        if node is not None and any(call is node for call, _, _ in macro_calls):
            message = f"{message} (calling macro `{node.tagName.removeprefix('xacro:')}`)"
        chain = _chain([(name, site) for call, name, site in macro_calls if call is not node])
        if chain:
            message = f"{message} (in macro {chain})"
        return InputError(f"xacro: {message}", source.path, source.line, source.column)


@contextlib.contextmanager
def _patched(xacro, session: _Session, stamping: bool = True) -> Iterator[None]:
    """Install the hooks (the caller holds ``_LOCK``) and restore xacro exactly afterwards."""
    from xacro import substitution_args

    patches: list[tuple[Any, str, Any]] = [
        (substitution_args, "_eval_find", session.find),
    ]
    if stamping:
        patches += [
            (xacro, "parse", session.parse),
            (xacro, "handle_macro_call", session.handle_macro_call(xacro.handle_macro_call)),
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


def _parse_stamped(data: bytes, shown: str):
    """Parse with expat into minidom, every element stamped with ``Source(shown, line, col)``."""
    from xml.dom import expatbuilder
    from xml.parsers import expat

    class Builder(expatbuilder.ExpatBuilderNS):
        def install(self, parser) -> None:
            super().install(parser)
            parser.EntityDeclHandler = self.refuse_entity
            parser.ExternalEntityRefHandler = self.refuse_entity

        def refuse_entity(self, *_args) -> None:
            raise InputError(safexml.NO_ENTITIES, shown, self._parser.CurrentLineNumber)

        def start_element_handler(self, name, attributes) -> None:
            super().start_element_handler(name, attributes)
            parser = self._parser
            source = Source(shown, parser.CurrentLineNumber, parser.CurrentColumnNumber + 1)
            self.curNode.setUserData(_STAMP, source, _COPY_STAMP)

    try:
        return Builder().parseString(data)
    except expat.ExpatError as error:
        raise InputError(
            f"not well-formed XML: {expat.ErrorString(error.code)}",
            shown,
            error.lineno,
            error.offset + 1,
        ) from None


def _elements(node) -> Iterator[Any]:
    """``node`` and its element descendants, document order."""
    stack = [node]
    while stack:
        current = stack.pop()
        if current.nodeType == Node.ELEMENT_NODE:
            yield current
            stack.extend(reversed(current.childNodes))


# --- minidom to lxml ------------------------------------------------------------------------


def _to_lxml(root, fallback: Source) -> tuple[etree._Element, dict[Any, Source]]:
    """
    Serialise the expanded minidom tree (attributes in document order, not xacro's sorted
    order) and parse it with lxml; pair elements in document order to carry the stamps over.
    """
    from lxml import etree

    out: list[str] = []
    sources: list[Source] = []
    _write(root, out, sources, fallback)
    try:
        lxml_root = etree.fromstring("".join(out).encode("utf-8"), safexml.parser(huge_tree=True))
    except etree.XMLSyntaxError as error:
        raise InputError(f"xacro produced XML lxml cannot read: {error}", fallback.path) from None
    elements = list(lxml_root.iter(etree.Element))
    if len(elements) != len(sources):  # pragma: no cover - serialisation is one-to-one
        raise InputError("internal error: expanded tree does not round-trip", fallback.path)
    return lxml_root, dict(zip(elements, sources, strict=True))


def _write(node, out: list[str], sources: list[Source], inherited: Source) -> None:
    # saxutils pulls in urllib, http and email (~20 ms): import it only to write xacro output
    from xml.sax.saxutils import escape, quoteattr

    kind = node.nodeType
    if kind == Node.ELEMENT_NODE:
        source = node.getUserData(_STAMP) or inherited
        sources.append(source)
        out.append("<" + node.tagName)
        for name, value in node.attributes.items():
            out.append(f" {name}={quoteattr(value)}")
        if not node.childNodes:
            out.append("/>")
            return
        out.append(">")
        for child in node.childNodes:
            _write(child, out, sources, source)
        out.append(f"</{node.tagName}>")
    elif kind in (Node.TEXT_NODE, Node.CDATA_SECTION_NODE):
        out.append(escape(node.data))
    elif kind == Node.COMMENT_NODE:
        text = node.data.replace("--", "- -")
        out.append(f"<!--{text}{' ' if text.endswith('-') else ''}-->")


# --- errors ---------------------------------------------------------------------------------


def _cause(error: BaseException, kind: type) -> Any:
    """The first exception of ``kind`` among ``error``, what it wraps and what caused it."""
    seen: set[int] = set()
    todo = [error]
    while todo:
        current = todo.pop(0)
        if current is None or id(current) in seen:
            continue
        seen.add(id(current))
        if isinstance(current, kind):
            return current
        todo += [getattr(current, "exc", None), current.__cause__, current.__context__]
    return None


def _fault_site(error: BaseException, xacro_file: str) -> tuple[Any, list[tuple[Any, str, Any]]]:
    """
    The innermost DOM node xacro was working on when ``error`` was raised (a local ``node`` or
    ``elt`` of xacro's functions), and the macro calls being expanded, outermost first.
    """
    innermost = None
    calls: list[tuple[str, Any]] = []
    xacro_dir = os.path.dirname(xacro_file)
    for frame, _ in traceback.walk_tb(error.__traceback__):
        if os.path.dirname(frame.f_code.co_filename) != xacro_dir:
            continue
        local = frame.f_locals
        node = local.get("node", local.get("elt"))
        if node is None or not hasattr(node, "nodeType"):
            continue
        innermost = node
        if frame.f_code.co_name == "handle_macro_call" and node.nodeType == Node.ELEMENT_NODE:
            calls.append((node, node.tagName.removeprefix("xacro:"), node.getUserData(_STAMP)))
    return innermost, calls


def _chain(calls: list[tuple[str, Any]], keep: int = 4) -> str:
    """``calls`` outermost first, repeats (a recursive macro) folded, at most ``keep`` shown."""
    folded: list[list[Any]] = []
    for name, site in calls:
        if site is None:
            continue
        if folded and folded[-1][:2] == [name, site]:
            folded[-1][2] += 1
        else:
            folded.append([name, site, 1])
    parts = [
        f"`{name}` called at {site}" + (f" ({count} times)" if count > 1 else "")
        for name, site, count in folded
    ]
    if len(parts) > keep:
        parts = [*parts[: keep - 1], f"{len(parts) - keep} more", parts[-1]]
    return ", ".join(parts)


def _source_near(node) -> Source | None:
    while node is not None:
        if node.nodeType == Node.ELEMENT_NODE:
            source = node.getUserData(_STAMP)
            if source is not None:
                return Source(source.path, source.line, source.column)
        node = node.parentNode
    return None


def _message(error: BaseException) -> str:
    import xacro
    from xacro.substitution_args import ArgException

    argument = _cause(error, ArgException)
    if argument is not None:
        name = str(argument)
        return (
            f"undefined substitution argument `{name}`: pass --xacro-arg {name}:=VALUE or "
            f'declare <xacro:arg name="{name}" default="..."/>'
        )
    missing = _cause(error, OSError)
    if isinstance(error, xacro.XacroException) and missing is not None:
        reason = missing.strerror or str(missing)
        return f"cannot read include {missing.filename or ''}: {reason}".replace(" :", ":")
    text = " ".join(str(error).split()) or type(error).__name__
    if text.startswith("unknown macro name"):
        text += ": is the file that defines it included, and the name spelled alike?"
    return text
