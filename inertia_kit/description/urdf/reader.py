"""
A ``.urdf`` or xacro file, parsed safely, into the model with the source location of every
element (:func:`load_urdf`, which :func:`inertia_kit.description.loader.load` calls for anything
that is not MJCF). Raises :class:`~inertia_kit.errors.InputError` for anything that is not a
readable robot description; never a traceback.

Xacro that uses xacro goes through :mod:`.xacro_expand`, anything else is parsed as XML
(:mod:`inertia_kit.description.xmlparse`); either tree becomes the model in :mod:`.builder`.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.reads import digest, key
from inertia_kit.description.urdf.builder import Builder
from inertia_kit.description.xmlparse import element_locator, parse_xml
from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from inertia_kit.description.xacro_limits import XacroLimits

# Anything xacro would change: without it, a file that declares the xacro namespace (as xacro's
# own output does) is plain URDF, and xacro would give it back unchanged
_XACRO_AT_WORK = re.compile(rb"<\s*xacro:|\$\{|\$\(")
# xacro leaves comments as they are (unless a comment turns ``xacro:eval-comments`` on): a
# ``${...}`` in one is no use of xacro. Not taken out where a CDATA section could hold a ``<!--``
_COMMENT = re.compile(rb"<!--.*?-->", re.DOTALL)
_COMMENTS_READ = (b"xacro:eval-comments", b"<![CDATA[")


def needs_expansion(data: bytes) -> bool:
    """
    Whether a file must go through xacro: xacro by content *and* using it (macros, ``${}``,
    ``$()`` outside comments). A file that only declares the namespace, as xacro's own output
    does, is URDF, and so is one whose only ``${}`` are in comments (PR2's, generated with
    ``${cal_head_x}`` quoted in them).
    """
    from inertia_kit.description.urdf.xacro_detect import is_xacro

    data = narrow(data)
    if not is_xacro(data):
        return False
    if not any(mark in data for mark in _COMMENTS_READ):
        data = without_comments(data)
    return _XACRO_AT_WORK.search(data) is not None


def without_comments(data: bytes) -> bytes:
    """
    ``data`` with its ``<!-- … -->`` comments taken out, in time linear in its length: only up
    to the last ``-->``, so every ``<!--`` the pattern tries has an end and is matched (a
    ``<!--`` with none after it would otherwise make the pattern scan to the end of the text
    once for each, quadratic in a hostile file of them); what follows is kept as it is.
    """
    end = data.rfind(b"-->")
    if end < 0:
        return data
    return _COMMENT.sub(b"", data[: end + 3]) + data[end + 3 :]


def narrow(data: bytes) -> bytes:
    """UTF-16/32 text (by byte-order mark) as UTF-8, to look for xacro in; other data as it is."""
    for mark, codec in ((b"\xff\xfe\x00\x00", "utf-32"), (b"\x00\x00\xfe\xff", "utf-32")):
        if data.startswith(mark):
            return data.decode(codec, "replace").encode("utf-8")
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        return data.decode("utf-16", "replace").encode("utf-8")
    return data


def load_urdf(
    path: str | Path,
    data: bytes,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    xacro_limits: XacroLimits | None = None,
) -> model.Robot:
    """
    Load a URDF or xacro robot description whose bytes, read within bounds and checked as
    text, are ``data``.

    The parameters are :func:`inertia_kit.description.loader.load`'s.

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
    from inertia_kit.description.urdf.packages import PackageResolver
    from inertia_kit.description.urdf.xacro_detect import is_fragment, is_xacro

    path = Path(path)
    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)

    xacro = is_xacro(data)
    if needs_expansion(data):
        from inertia_kit.description.urdf.xacro_expand import expand  # plain URDF: not imported

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


def expanded_text(
    path: Path,
    output: Path,
    *,
    package_paths: Iterable[str | Path] = (),
    xacro_args: Mapping[str, str] | None = None,
    limits: XacroLimits | None = None,
) -> tuple[str, model.Robot]:
    """The expanded URDF of the xacro file ``path`` as text (indented two spaces, with a
    comment naming its source), and its model with the lines of that text; meshes and
    packages resolve as from ``path``."""
    import copy

    from lxml import etree

    from inertia_kit.description.urdf.packages import PackageResolver
    from inertia_kit.description.urdf.xacro_expand import expand
    from inertia_kit.description.xmlparse import parse_xml, start_tag_positions

    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)
    expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver, limits=limits)
    if expanded.fragment:
        raise InputError("a xacro fragment without links: no robot to write", path)
    root = copy.deepcopy(expanded.root)
    for element in root.iter():
        if element.text is not None and not element.text.strip():
            element.text = None
        if element.tail is not None and not element.tail.strip():
            element.tail = None
    etree.indent(root, space="  ")
    comment = f"generated by inertia-fill from {path.name}: edit that file, not this one"
    body = etree.tostring(root, encoding="unicode")
    text = f'<?xml version="1.0" encoding="utf-8"?>\n<!-- {comment} -->\n{body}\n'
    data = text.encode("utf-8")
    tree = parse_xml(data, output)
    positions = start_tag_positions(data, tree) or {}
    # the same elements in the same order: where each came from in the xacro sources
    origins = dict(zip(tree.iter(etree.Element), expanded.root.iter(etree.Element), strict=True))

    def source_of(element: etree._Element) -> model.Source:
        parent = element.getparent()
        if parent is not None and parent.tag == "geometry":
            # relative mesh paths resolve from the file that wrote them, as for the xacro
            return expanded.source_of(origins[element])
        line, column = positions.get(element, (element.sourceline, None))
        return model.Source(str(output), line, column)

    robot = Builder(path, source_of, resolver, tuple(expanded.files)).robot(tree)
    return text, robot


def files_read(
    path: str | Path,
    *,
    xacro_args: Mapping[str, str] | None = None,
    package_paths: Iterable[str | Path] = (),
    limits: XacroLimits | None = None,
) -> tuple[tuple[str, ...], bool]:
    """
    The files the xacro expansion of ``path`` reads (the input first) and whether it is a
    fragment (no link once expanded); ``InputError`` for what xacro refuses.
    """
    from inertia_kit.description.urdf.packages import PackageResolver
    from inertia_kit.description.urdf.xacro_expand import expand

    resolver = PackageResolver(package_paths=tuple(package_paths), start=path)
    expanded = expand(path, args=dict(xacro_args or {}), resolver=resolver, limits=limits)
    return tuple(expanded.files), expanded.fragment
