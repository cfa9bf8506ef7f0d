"""
``inertia-fill -o OUT``: the filled robot goes to a new file and the input is not touched.

A URDF input gives its own bytes with the edits; a xacro input gives the fully expanded URDF
(two-space indentation, comments dropped), in which links made by macros or includes are filled
too (in place they are refused). Relative mesh paths are resolved, and written, as in the xacro
sources.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from inertia_kit.errors import InputError

if TYPE_CHECKING:
    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.model import Robot
    from inertia_kit.description.xacro_limits import XacroLimits
    from inertia_kit.fill.plan import FillPlan


def output_source(
    path: Path,
    output: Path,
    package_paths: Sequence[str | Path],
    xacro_args: Mapping[str, str] | None,
    xacro_limits: XacroLimits | None = None,
) -> tuple[SourceText, Robot]:
    """
    What filling ``path`` into the new file ``output`` fills: the input's bytes and robot for a
    URDF file; for a xacro file, the fully expanded URDF as text (named ``output``) and its
    robot, so that links produced by macros or includes can be filled too.

    Raises ``InputError`` when the file cannot be read, for a xacro fragment (no robot to write),
    and when ``output`` is ``path`` itself.
    """
    from inertia_kit.description.edits import SourceText
    from inertia_kit.description.loader import expanded, load, needs_expansion
    from inertia_kit.description.reads import as_loaded
    from inertia_kit.description.safexml import read_bounded

    if os.path.exists(output) and os.path.exists(path) and output.resolve() == path.resolve():
        raise InputError("-o names the input file itself; give another output file", path)
    if needs_expansion(read_bounded(path)):
        text, robot = expanded(
            path, output, package_paths=package_paths, xacro_args=xacro_args, limits=xacro_limits
        )
        return SourceText(str(output), text.encode("utf-8"), text, "utf-8", b""), robot
    # a URDF file: its own bytes, edited (offsets into them), written elsewhere
    robot = load(path, package_paths=package_paths, xacro_limits=xacro_limits)
    if robot.fragment:
        raise InputError("a xacro fragment without links: no robot to write", path)
    return as_loaded(path, dict(robot.reads)), robot


def write_output(plan: FillPlan, follow_symlinks: bool = False) -> bool:
    """
    Write ``plan``'s filled text to its ``path`` (a plan of ``plan_fill(..., output=...)``),
    atomically, creating the file if need be; an existing file keeps its permission bits and
    is left alone when it already holds these bytes. Returns whether the file was written;
    ``InputError`` for a folder, a missing folder or a read-only file, and, unless
    ``follow_symlinks``, for a path that is or passes through a symbolic link
    (:mod:`~inertia_kit.description.output_paths`).
    """
    from inertia_kit.description.edits import write_atomic
    from inertia_kit.description.output_paths import refuse_links

    if plan.source is None:
        return False
    refuse_links(plan.path, follow_symlinks)
    return write_atomic(plan.path, plan.new_bytes, create=True, follow_symlinks=follow_symlinks)
