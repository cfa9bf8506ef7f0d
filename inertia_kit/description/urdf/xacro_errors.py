"""
Errors of a xacro expansion, told as a user can act on them: the file, line and column of the
element xacro was working on (found in the traceback's frames), the macro calls that led there,
and a message that says what to pass or declare.
"""

from __future__ import annotations

import os
import traceback
from collections.abc import Callable
from typing import Any
from xml.dom import Node

from inertia_kit.description.model import Source
from inertia_kit.description.urdf.xacro_source_map import stamp_of
from inertia_kit.description.xacro_limits import LimitExceeded
from inertia_kit.errors import InputError

_PACKAGE_HINT = "pass --package-path DIR with the package folder or a folder that holds it"


class PackageNotFound(LookupError):
    """``$(find pkg)`` named a package that no search found."""

    def __init__(self, package: str, near: str, searched: tuple[str, ...] = ()):
        self.package = package
        places = "; ".join(searched) or (
            f"--package-path, ROS_PACKAGE_PATH, AMENT_PREFIX_PATH and the folders above {near}"
        )
        super().__init__(
            f"package `{package}` not found for $(find {package}) (searched {places}): "
            f"{_PACKAGE_HINT}"
        )


def input_error(
    error: BaseException,
    path: str,
    display: Callable[[str], str],
    out_of_memory: LimitExceeded | None = None,
) -> InputError:
    """
    An :class:`InputError` for what xacro raised while expanding ``path``, at the innermost
    element it was on; ``display`` shows an included file's name as the user should see it;
    ``out_of_memory`` says what a ``MemoryError`` means (the memory limit). A limit's hint
    (how to raise it) comes last.
    """
    import xacro

    not_found = _cause(error, PackageNotFound)
    node, macro_calls = _fault_site(error, xacro.__file__)
    source = _source_near(node)
    if source is None:
        stack = [f for f in (xacro.filestack or []) if f]
        source = Source(display(stack[-1]) if len(stack) > 1 else path)
    message = str(not_found) if not_found is not None else _message(error)
    exceeded = _cause(error, LimitExceeded)
    if _cause(error, MemoryError) is not None:
        exceeded = out_of_memory or LimitExceeded("out of memory")
        # the expression xacro was evaluating, if any: "when evaluating expression '...'"
        message = str(exceeded) if message == "MemoryError" else f"{exceeded} ({message})"
    if node is not None and any(call is node for call, _, _ in macro_calls):
        message = f"{message} (calling macro `{node.tagName.removeprefix('xacro:')}`)"
    chain = _chain([(name, site) for call, name, site in macro_calls if call is not node])
    if chain:
        message = f"{message} (in macro {chain})"
    if exceeded is not None and exceeded.hint:
        message = f"{message}; {exceeded.hint}"
    return InputError(f"xacro: {message}", source.path, source.line, source.column)


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
            calls.append((node, node.tagName.removeprefix("xacro:"), stamp_of(node)))
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
            source = stamp_of(node)
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
