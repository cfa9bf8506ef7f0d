"""
Robot descriptions in: a ``.urdf`` or xacro file, parsed safely, into the model with the source
location of every element. Raises :class:`~inertia_kit.errors.InputError` for anything that is
not a readable robot description; never a traceback.

:func:`load` picks the way in: xacro that uses xacro goes through :mod:`.xacro_expand`, anything
else is parsed as XML (:mod:`.xmlparse`); either tree becomes the model in :mod:`.builder`.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.builder import Builder
from inertia_kit.description.mjcf.detect import is_mjcf
from inertia_kit.description.reads import digest, key
from inertia_kit.description.safexml import read_bounded
from inertia_kit.description.xmlparse import check_text, element_locator, parse_xml

if TYPE_CHECKING:
    from inertia_kit.description.xacro_limits import XacroLimits

# Anything xacro would change: without it, a file that declares the xacro namespace (as xacro's
# own output does) is plain URDF, and xacro would give it back unchanged
_XACRO_AT_WORK = re.compile(rb"<\s*xacro:|\$\{|\$\(")


def needs_expansion(data: bytes) -> bool:
    """
    Whether a file must go through xacro: xacro by content *and* using it (macros, ``${}``,
    ``$()``). A file that only declares the namespace, as xacro's own output does, is URDF.
    """
    from inertia_kit.description.xacro_detect import is_xacro

    data = _narrow(data)
    return is_xacro(data) and _XACRO_AT_WORK.search(data) is not None


def _narrow(data: bytes) -> bytes:
    """UTF-16/32 text (by byte-order mark) as UTF-8, to look for xacro in; other data as it is."""
    for mark, codec in ((b"\xff\xfe\x00\x00", "utf-32"), (b"\x00\x00\xfe\xff", "utf-32")):
        if data.startswith(mark):
            return data.decode(codec, "replace").encode("utf-8")
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data.decode("utf-16", "replace").encode("utf-8")
    return data


def load(
    path: str | Path,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
) -> model.Robot:
    """
    Load a URDF or xacro robot description.

    Parameters
    ----------
    path : str or Path
      A ``.urdf``, ``.xacro`` or ``.urdf.xacro`` file; xacro is recognised by content.
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
      A fragment (a xacro file, by name or content, with no ``<link>`` and no ``<joint>``
      once expanded: macros, properties, materials, ``<gazebo>`` blocks) loads as a robot with
      no links and ``fragment=True``. Its ``reads`` hold a digest of the bytes of every file
      read (the input, every xacro file included), which edits of them check (:mod:`.reads`).

    Raises
    ------
    InputError
      For anything that is not a readable robot description: a missing, unreadable, empty,
      binary or oversized file, malformed XML, entity declarations, a root other than
      ``<robot>``, anything xacro refuses, or a xacro expansion past a limit. Missing
      meshes and non-numeric values are not errors: they are recorded on the model
      (``Mesh.problem``, ``Robot.invalid``).
    """
    from inertia_kit.description.packages import PackageResolver
    from inertia_kit.description.xacro_detect import is_fragment, is_xacro

    path = Path(path)
    data = read_bounded(path)
    check_text(data, path)
    if is_mjcf(_narrow(data)):
        from inertia_kit.description.mjcf.reader import load_mjcf

        return load_mjcf(path)
    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)

    xacro = is_xacro(data)
    if needs_expansion(data):
        from inertia_kit.description.xacro_expand import expand  # plain URDF: not imported

        expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver, limits=xacro_limits)
        read = tuple(expanded.reads.items())
        if expanded.fragment:
            return _fragment(path, expanded.files, read)
        robot = Builder(path, expanded.source_of, resolver, tuple(expanded.files)).robot(
            expanded.root
        )
        return dataclasses.replace(
            robot, environment_values=expanded.environment_values, reads=read
        )

    read = ((key(path), digest(data)),)
    root = parse_xml(data, path)
    if (xacro or path.name.lower().endswith(".xacro")) and is_fragment(root):
        # as expand() classes a xacro file without links
        return _fragment(path, (str(path),), read)
    position = element_locator(data, root)

    def source_of(element: etree._Element) -> model.Source:
        return model.Source(str(path), *position(element))

    robot = Builder(path, source_of, resolver, (str(path),)).robot(root)
    return dataclasses.replace(robot, reads=read)


def _fragment(
    path: Path, files: Iterable[str], read: tuple[tuple[str, str | None], ...]
) -> model.Robot:
    return model.Robot(
        None, (), (), (), model.Source(str(path), 1), tuple(files), (), True, reads=read
    )
