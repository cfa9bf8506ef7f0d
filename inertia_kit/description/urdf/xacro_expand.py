"""
Xacro expansion through the real ``xacro`` package, without ROS, with a source map.

:func:`expand` runs xacro in-process on files parsed by our own expat builder, which stamps every
element with its file, line and column (DOM user data, which minidom copies onto clones, so the
stamps survive macro expansion; see :mod:`.xacro_source_map`). Four xacro internals are
replaced for the duration of the call, by the hooks of :mod:`.xacro_session`:

- ``xacro.parse``: files (the input and every include) are size-checked and refused if they
  declare entities, then parsed with the stamping builder;
- ``xacro.handle_macro_call``: elements a macro produced get the call site appended to their
  stamp's ``calls`` (outer calls are prepended later, so ``calls`` reads outermost first);
- ``xacro.substitution_args._eval_find``: ``$(find pkg)`` goes to a
  :class:`~inertia_kit.description.urdf.packages.PackageResolver` instead of ``ament_index_python``;
  ``xacro.eval_text`` is wrapped to see the path that follows it (``$(find pkg)/urdf/arm.xacro``),
  so that, as for a mesh, the candidate folder holding that path wins;
- ``xacro.safe_eval``: expressions run with ``**``, ``*`` and ``<<`` checked
  (:func:`~inertia_kit.description.xacro_limits.guarded_code`).
- ``$(env)``, ``$(optenv)`` and ``xacro.load_yaml`` are wrapped to record what the environment
  gives (:attr:`Expanded.environment_values`, for ``--redact-env``: :mod:`.redaction`).

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
import threading
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any
from xml.dom import Node

from inertia_kit.description.model import Source
from inertia_kit.description.urdf.xacro_errors import input_error
from inertia_kit.description.urdf.xacro_sandbox import Expansion
from inertia_kit.description.urdf.xacro_session import Session, patched
from inertia_kit.description.urdf.xacro_source_map import to_lxml
from inertia_kit.description.xacro_limits import LimitExceeded, Meter, XacroLimits
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from lxml import etree

    from inertia_kit.description.urdf.packages import PackageResolver

#: Top-level tags of a file meant to be included rather than expanded on its own.
FRAGMENT_TAGS = frozenset({"xacro:macro", "xacro:property", "xacro:arg", "xacro:include"})

_LOCK = threading.Lock()


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
    environment_values : tuple of str
      What the environment gave: ``$(env)``, ``$(optenv)``, YAML values
      (:mod:`~inertia_kit.description.redaction`).
    reads : mapping of str to str
      Every file read, by real path: a digest of the bytes read (:mod:`.reads`).
    """

    path: str
    root: etree._Element
    files: tuple[str, ...]
    fragment: bool
    warnings: tuple[str, ...] = ()
    _sources: Mapping[Any, Source] = field(default_factory=dict, repr=False, compare=False)
    environment_values: tuple[str, ...] = ()
    # real path -> digest of the bytes read, of every file read (description.reads)
    reads: Mapping[str, str | None] = field(default_factory=dict, repr=False, compare=False)

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

    from inertia_kit.description.urdf import xacro_sandbox
    from inertia_kit.description.urdf.packages import PackageResolver

    shown = str(path)
    if resolver is None:
        resolver = PackageResolver(start=path)
    if limits is None:
        limits = XacroLimits.resolve()
    start = time.monotonic()
    room = xacro_sandbox.memory_room_mb()  # an inherited limit below the xacro one: it speaks

    def work() -> Expansion:
        return _expand(shown, dict(args or {}), resolver, limits, start, room)

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
        memory = limits.out_of_memory(room)
        if isinstance(error, xacro_sandbox.ChildDied):
            memory = LimitExceeded(f"{memory} ({error.reason()})", memory.hint)
        raise InputError(f"xacro: {memory.told()}", shown) from None
    if result.resolver_state:
        vars(resolver).update(result.resolver_state)
    return _expanded(result)


def _expanded(result: Expansion) -> Expanded:
    """The expansion handed over (from the child) as the lxml tree and its source map."""
    from lxml import etree

    from inertia_kit.description.urdf.xacro_detect import is_fragment

    environment = result.environment_values
    reads = result.reads or {}
    if result.text is None or result.sources is None:
        return Expanded(
            result.path, etree.Element("robot"), result.files, True, result.warnings, reads=reads
        )
    root, sources = to_lxml(result.text, result.sources, Source(result.path))
    if is_fragment(root):
        return Expanded(
            result.path,
            etree.Element("robot"),
            result.files,
            True,
            result.warnings,
            environment_values=environment,
            reads=reads,
        )
    return Expanded(
        result.path, root, result.files, False, result.warnings, sources, environment, reads
    )


def _expand(
    shown: str,
    args: dict[str, str],
    resolver: PackageResolver,
    limits: XacroLimits,
    start: float,
    room: float | None = None,
) -> Expansion:
    """The expansion itself (in the child process, or in-process under ``_LOCK``)."""
    import xacro

    session = Session(shown, resolver, Meter(limits, start))
    with patched(xacro, session):
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
                error, session.path, session.display, limits.out_of_memory(room)
            ) from None
        return session.result(doc.documentElement)
