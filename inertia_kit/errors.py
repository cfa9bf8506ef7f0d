"""The errors inertia-kit raises on bad input, each naming the file (and line) at fault."""

from __future__ import annotations

from pathlib import Path


class InertiaKitError(Exception):
    """Base class of every error a user can cause through input."""


class InputError(InertiaKitError):
    """
    A file we cannot read as a robot description: the command exits 2.

    ``str(error)`` is ``path:line:column: message`` with as much of the location as is known.
    ``environment_values``: what the environment gave the xacro expansion that failed
    (``--redact-env`` keeps them out of the message as printed).
    """

    environment_values: tuple[str, ...] = ()

    def __init__(
        self,
        message: str,
        path: str | Path | None = None,
        line: int | None = None,
        column: int | None = None,
    ):
        self.message = message
        self.path = None if path is None else str(path)
        self.line = line
        self.column = column
        super().__init__(str(self))

    def __str__(self) -> str:
        location = ":".join(
            str(part) for part in (self.path, self.line, self.column) if part is not None
        )
        return f"{location}: {self.message}" if location else self.message


class MeshError(InertiaKitError):
    """
    A mesh file that yields no mass properties.

    ``kind`` is ``not-found``, ``unreadable`` (corrupt or unsupported), ``empty`` (no volume) or
    ``overflow`` (its volume or moments, scaled, leave double precision).
    """

    def __init__(self, path: str | Path, kind: str, message: str):
        self.path = str(path)
        self.kind = kind
        self.message = message
        super().__init__(f"{self.path}: {message}")


class ConfigError(InertiaKitError):
    """Bad configuration or usage: the command exits 2."""


class InternalError(InertiaKitError):
    """
    An exception inertia-kit did not foresee while processing a file: a bug in inertia-kit, not
    in the file. The commands report it for that file and exit 2, never 1 (findings).

    Shaped like :class:`InputError` (``message``, ``path``, ``line``, ``column``) so that the
    outputs that list unreadable files list it too; ``error`` is the exception itself.
    """

    def __init__(self, error: BaseException, path: str | Path | None = None):
        self.error = error
        self.path = None if path is None else str(path)
        self.line = None
        self.column = None
        what = f"{type(error).__name__}: {error}" if str(error) else type(error).__name__
        self.message = (
            f"internal error: {what}; this is a bug in inertia-kit, not in the file: please "
            "report it with the file and the command line (INERTIA_KIT_TRACEBACK=1 prints "
            "the traceback)"
        )
        super().__init__(str(self))

    def __str__(self) -> str:
        return f"{self.path}: {self.message}" if self.path else self.message
