"""
Robot descriptions in, whatever their format: :func:`load` reads a file within bounds, checks
that it is text, and hands it to its format's reader by content: an MJCF model (root
``<mujoco>``: :mod:`.mjcf.reader`), else URDF or xacro (:mod:`.urdf.reader`). Every reader
gives the one model (:mod:`.model`) with the source location of every element, and raises
:class:`~inertia_kit.errors.InputError` for anything that is not a readable robot
description; never a traceback. A third format (SDFormat, USD) is a third reader here.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.description import model
from inertia_kit.description.mjcf.detect import is_mjcf
from inertia_kit.description.safexml import read_bounded
from inertia_kit.description.urdf.reader import expanded_text as expanded
from inertia_kit.description.urdf.reader import files_read, load_urdf, narrow, needs_expansion
from inertia_kit.description.urdf.xacro_includes import is_xml, reads_others
from inertia_kit.description.urdf.xacro_includes import reach as files_reached
from inertia_kit.description.xmlparse import check_text

if TYPE_CHECKING:
    from inertia_kit.description.xacro_limits import XacroLimits

#: what the layers above read descriptions through: ``needs_expansion`` (a file made by macros,
#: xacro), ``files_read`` (what such a file's expansion reads: the include graph),
#: ``files_reached``, ``is_xml`` and ``reads_others`` (what its includes as written may read,
#: without expanding it: the include graph's filters), ``expanded`` (its expansion as text, for
#: ``inertia-fill -o``), ``may_be_included`` and ``stand_in_suffix`` (a text read from stdin),
#: besides :func:`load`
__all__ = [
    "expanded",
    "files_reached",
    "files_read",
    "format_of",
    "is_xml",
    "load",
    "may_be_included",
    "needs_expansion",
    "reads_others",
    "stand_in_suffix",
]


def format_of(data: bytes) -> str:
    """The format of a description's text, by content: ``mjcf`` (root ``<mujoco>``) or
    ``urdf`` (URDF or xacro: anything else, which its reader accepts or refuses)."""
    return "mjcf" if is_mjcf(narrow(data)) else "urdf"


def may_be_included(data: bytes) -> bool:
    """Whether a text may be a fragment that URDF robots include (xacro, by content); an
    MJCF file is a model of its own (the files it includes are read with it)."""
    from inertia_kit.description.urdf.xacro_detect import is_xacro

    return format_of(data) == "urdf" and is_xacro(data)


def stand_in_suffix(data: bytes) -> str:
    """The file name suffix a text read from stdin is linted under: its format's."""
    if format_of(data) == "mjcf":
        return ".xml"
    return ".urdf.xacro" if may_be_included(data) else ".urdf"


def load(
    path: str | Path,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
) -> model.Robot:
    """
    Load a robot description: MJCF, URDF or xacro, told apart by content.

    Parameters
    ----------
    path : str or Path
      The file (``.xml``, ``.urdf``, ``.xacro``, ``.urdf.xacro``, any name).
    xacro_args : mapping, optional
      ``name -> value`` for ``$(arg name)``, as ``name:=value`` on xacro's command line.
    package_paths : iterable of paths
      Folders searched first for ``$(find pkg)`` and ``package://pkg`` (a package, or a folder
      of packages).
    xacro_limits : XacroLimits, optional
      Time, memory and element limits of a xacro expansion; by default
      ``XacroLimits.resolve()``: the defaults and ``INERTIA_KIT_XACRO_LIMITS``.

    Returns
    -------
    robot : Robot
      See :func:`.urdf.reader.load_urdf` and :func:`.mjcf.reader.load_mjcf`; ``robot.format``
      says which (``urdf``, ``mjcf``).

    Raises
    ------
    InputError
      A missing, unreadable, empty, binary or oversized file, or anything its format's reader
      refuses.
    """
    path = Path(path)
    data = read_bounded(path)
    check_text(data, path)
    if is_mjcf(narrow(data)):
        from inertia_kit.description.mjcf.reader import load_mjcf

        return load_mjcf(path)
    return load_urdf(
        path, data, xacro_args=xacro_args, package_paths=package_paths, xacro_limits=xacro_limits
    )
