"""
Files read as a run holds them in memory, not as the disk does: ``inertia-lint --fix`` lints
each pass on the text the previous pass produced and writes every file once, at the end, so
that a run killed between two passes leaves every file as it was (not half fixed).

:func:`overlaid` is the one way in: within it, every read of a robot description or xacro file
(:func:`~inertia_kit.description.safexml.read_bounded`: the loader, xacro's includes, text read
for editing, suppression comments) gets the overlay's bytes for a file it holds, named by real
path (:func:`~inertia_kit.description.reads.key`), and the disk's for any other. It is a context
variable, so it reaches a xacro expansion's forked child (which inherits the parent's state)
and no other thread or run; it holds a copy of the mapping, so nothing changes it while it is
in force.
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Iterator, Mapping
from pathlib import Path
from types import MappingProxyType

from inertia_kit.description.reads import key

_NONE: Mapping[str, bytes] = MappingProxyType({})
_TEXTS: contextvars.ContextVar[Mapping[str, bytes]] = contextvars.ContextVar(
    "inertia_kit_overlay", default=_NONE
)


@contextlib.contextmanager
def overlaid(texts: Mapping[str, bytes]) -> Iterator[None]:
    """Within the block, a file whose real path ``texts`` holds reads as its bytes there (an
    overlay in force still holds the others: a fix probing an expansion during a pass)."""
    token = _TEXTS.set(MappingProxyType({**_TEXTS.get(), **texts}))
    try:
        yield
    finally:
        _TEXTS.reset(token)


def overlay_bytes(path: str | Path) -> bytes | None:
    """The bytes the overlay in force holds for ``path``, or ``None`` (read the disk)."""
    texts = _TEXTS.get()
    if not texts:
        return None
    return texts.get(key(path))
