"""
Reading XML we did not write, safely: a size bound, no entity declarations (billion laughs,
external entities), and parsers that never touch the network or load a DTD. One place, used by
the URDF loader, the xacro expansion and package.xml lookups.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

from inertia_kit.description.overlay import overlay_bytes
from inertia_kit.errors import InputError
from inertia_kit.reading import read_regular, size_text

# larger than any real robot description (the biggest published ones are a few MB)
MAX_BYTES = 50 * 1024 * 1024

#: The most characters an attribute value, and an element or attribute name, of a robot
#: description may hold: far above any path (4096), name or list of numbers a robot needs, and
#: what keeps one value from filling every finding that quotes it (a xacro expression makes a
#: 100 MB name in 230 bytes). The same bounds for a file and for what an expansion returns.
MAX_VALUE_CHARS = 65_536
MAX_NAME_CHARS = 1_024

NO_ENTITIES = "entity declarations are not allowed: nothing was expanded or fetched"

_DOCTYPE = re.compile(rb"<!DOCTYPE\b")
_ENTITY = re.compile(rb"<!ENTITY\b")
_SUBSET_END = re.compile(rb"\]\s*>")


def read_bounded(path: str | Path, shown: str | Path | None = None) -> bytes:
    """
    The bytes of ``path``, refusing unreadable files, what is not a regular file (a named pipe,
    a device) and files over :data:`MAX_BYTES`, with an ``InputError`` naming ``shown``
    (default: ``path``). A file the overlay in force holds (:mod:`.overlay`: the passes of
    ``--fix``) reads as its bytes there.
    """
    data = overlay_bytes(path)
    if data is not None:
        check_size(data, path if shown is None else shown)
        return data
    return read_regular(path, MAX_BYTES, shown, what="robot description")


def check_size(data: bytes, shown: str | Path) -> None:
    if len(data) > MAX_BYTES:
        raise InputError(
            f"is larger than {size_text(MAX_BYTES)}; no robot description is that big "
            "(nothing was parsed)",
            shown,
        )


def oversized(tag: str, attributes) -> str | None:
    """
    What is too long in an element (its ``tag`` and its ``(name, value)`` ``attributes``),
    said in a few words; ``None`` when nothing is.
    """
    if len(tag) > MAX_NAME_CHARS:
        return f"an element name of {len(tag)} characters, more than the {MAX_NAME_CHARS}"
    for name, value in attributes:
        if len(name) > MAX_NAME_CHARS:
            return (
                f"<{tag}> has an attribute name of {len(name)} characters, more than the "
                f"{MAX_NAME_CHARS}"
            )
        if len(value) > MAX_VALUE_CHARS:
            return f"<{tag} {name}> holds {len(value)} characters, more than the {MAX_VALUE_CHARS}"
    return None


def too_long(what: str) -> str:
    """The message for :func:`oversized`'s finding."""
    return f"{what} a robot description may hold (nothing was read further)"


def refuse_entities(data: bytes, shown: str | Path) -> None:
    """
    Raise ``InputError`` (file, line, column) on an entity declaration, before any parser sees
    the bytes.

    Only a DOCTYPE's internal subset can declare entities, so only that is searched: a comment
    that mentions ``<!ENTITY`` is harmless. Parsers are configured to refuse any this
    byte-level look misses (another encoding, a ``]>`` inside an entity value).
    """
    doctype = _DOCTYPE.search(data)
    if doctype is None:
        return
    start = doctype.end()
    end = data.find(b">", start)
    subset = data.find(b"[", start)
    if subset != -1 and (end == -1 or subset < end):
        close = _SUBSET_END.search(data, subset)
        end = close.end() if close else len(data)
    entity = _ENTITY.search(data, start, len(data) if end == -1 else end)
    if entity is not None:
        from inertia_kit.description.lines import line_start, line_starts

        line = len(line_starts(data[: entity.start()]))
        column = entity.start() - line_start(data, entity.start()) + 1
        raise InputError(NO_ENTITIES, shown, line, column)


def parser(**options: Any):
    """An lxml parser that resolves no entity, loads no DTD and never uses the network."""
    from lxml import etree

    settings = {
        "resolve_entities": False,
        "no_network": True,
        "load_dtd": False,
        "huge_tree": False,
    }
    return etree.XMLParser(**{**settings, **options})
