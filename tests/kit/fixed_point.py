"""
Does a fill settle? Fill a copy of some robot files, fill again with the same options, and
name the files the second run changed (a fixed point changes none, and ``--check`` then passes
unless a link is refused).

The copy is a mirror of the package folder: folders made anew, robot files (``.urdf``,
``.xacro``) copied, every other file (meshes, ``package.xml``) a symbolic link to the original,
so mirroring a package of hundreds of megabytes costs almost nothing.

Used by ``tests/fill/test_fixed_point.py`` and by ``benchmarks/fixed_point.py`` (every example,
every rule document's failing example, every robot file of the installed PyPI packages).
"""

from __future__ import annotations

import os
import re
import shutil
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path

from kit import write

ROBOT_SUFFIXES = (".urdf", ".xacro")

#: mode -> the inertia-fill options of that mode (``mass`` adds ``--mass LINK=KG`` per file).
#: The numbers have many digits on purpose: rounding them is what used to make a second run
#: write other last digits.
MODES: dict[str, tuple[str, ...]] = {
    "missing": ("--fix", "missing"),
    "invalid": ("--fix", "invalid"),
    "all": ("--fix", "all"),
    "mass": ("--fix", "all"),
    "total-mass": ("--fix", "missing", "--total-mass", "12.3456789"),
    "density": ("--fix", "all", "--density", "2712.34567"),
    # inertia-lint applying the fixes its findings carry (the same machinery, lint's inputs)
    "lint-fix": ("--fix",),
    "lint-unsafe-fixes": ("--fix", "--unsafe-fixes"),
}
GIVEN_MASS = "1.23456789"


def robot_files(root: Path) -> list[Path]:
    """Every ``.urdf`` and ``.xacro`` file under ``root``, sorted."""
    return sorted(p for p in root.rglob("*") if p.suffix.lower() in ROBOT_SUFFIXES and p.is_file())


def mirror(root: Path, into: Path) -> Path:
    """A copy of ``root`` at ``into``: robot files copied, every other file linked."""
    for folder, _folders, files in os.walk(root):
        here = into / Path(folder).relative_to(root)
        here.mkdir(parents=True, exist_ok=True)
        for name in files:
            original = Path(folder) / name
            if original.suffix.lower() in ROBOT_SUFFIXES:
                shutil.copyfile(original, here / name)
            else:
                (here / name).symlink_to(original.resolve())
    return into


def first_link_with_geometry(path: Path, package_paths: Sequence[str]) -> str | None:
    """The name of the first link with geometry (for ``--mass``), ``None`` when none loads."""
    from inertia_kit.description.loader import load
    from inertia_kit.errors import InputError

    try:
        robot = load(path, package_paths=package_paths)
    except InputError:
        return None
    for link in robot.links:
        if link.collisions or link.visuals:
            return link.name
    return None


def run_fill(arguments: Sequence[str]) -> tuple[int, str]:
    """``inertia-fill ARGUMENTS`` in this process: exit code and what it printed."""
    from click.testing import CliRunner

    from inertia_kit.cli.fill import fill_command

    result = CliRunner().invoke(fill_command, list(arguments), catch_exceptions=False)
    return result.exit_code, result.output


def run_lint(arguments: Sequence[str]) -> tuple[int, str]:
    """``inertia-lint ARGUMENTS`` in this process: exit code and what it printed."""
    from click.testing import CliRunner

    from inertia_kit.cli.lint import lint_command

    result = CliRunner().invoke(lint_command, list(arguments), catch_exceptions=False)
    return result.exit_code, result.output


def _check(mode: str, options: Sequence[str], path: Path) -> bool:
    """Whether the run right after says nothing is left to change: ``inertia-fill --check``
    exits 0 (or refuses a link it says so); ``inertia-lint --diff`` shows no diff."""
    if mode.startswith("lint-"):
        flags = [o for o in options if o != "--fix"]
        _, output = run_lint([*flags, "--diff", str(path)])
        return "\n+++ " not in f"\n{output}"
    code, output = run_fill([*options, "--check", str(path)])
    return code != 1 or "not filled" in output


@dataclass
class Settling:
    """What a second fill did to the files a first fill wrote, for one mode."""

    mode: str
    files: int = 0
    changed_first: list[str] = field(default_factory=list)  # the files the first run changed
    changed_again: list[str] = field(default_factory=list)  # ... and the second run changed
    check_failed: list[str] = field(default_factory=list)  # --check exit 1 with no refusal
    crashed: list[str] = field(default_factory=list)  # an internal error or a traceback


def _snapshot(files: Iterable[Path]) -> dict[Path, tuple[int, int, int]]:
    """Each file's inode, modification time and size: a write (atomic, so a new inode) shows."""
    result = {}
    for path in files:
        status = path.stat()
        result[path] = (status.st_ino, status.st_mtime_ns, status.st_size)
    return result


def settle(
    root: Path,
    mode: str,
    *,
    package_paths: Sequence[str] = (),
    files: Sequence[Path] | None = None,
    progress: Callable[[str], None] | None = None,
) -> Settling:
    """
    Fill (or, for the ``lint-`` modes, fix with ``inertia-lint``) each robot file under ``root``
    (a mirror: it is written) in ``mode``, then do it again and compare. ``package_paths`` are
    given to every run; ``files`` limits the inputs.
    """
    result = Settling(mode)
    everything = robot_files(root)
    inputs = list(files) if files is not None else everything
    package_options = [option for p in package_paths for option in ("--package-path", str(p))]
    for path in inputs:
        options = [*MODES[mode], *package_options]
        if mode == "mass":
            link = first_link_with_geometry(path, package_paths)
            if link is None:
                continue
            options += ["--mass", f"{link}={GIVEN_MASS}"]
        result.files += 1
        before = _snapshot(everything)
        run = run_lint if mode.startswith("lint-") else run_fill
        _, output = run([*options, str(path)])
        if "internal error" in output or "Traceback" in output:
            result.crashed.append(str(path))
        middle = _snapshot(everything)
        if middle != before:
            result.changed_first.append(str(path))
        run([*options, str(path)])
        after = _snapshot(everything)
        if after != middle:
            result.changed_again.append(str(path))
        if not _check(mode, options, path) and str(path) not in result.changed_again:
            result.check_failed.append(str(path))
        if progress is not None:
            progress(str(path))
    return result


_EXAMPLE = re.compile(r"```xml fail(?: name=(\S+))?\n(.*?)```", re.DOTALL)
_MESH = re.compile(r"```stl name=(\S+)\n(.*?)```", re.DOTALL)


def rule_failing_examples(rules: Path, into: Path) -> Path:
    """Each rule document's ``fail`` examples (and the meshes they use) written under
    ``into/<document>/``, one folder per document."""
    for document in sorted(rules.glob("IN[0-9][0-9][0-9]-*.md")):
        text = document.read_text()
        folder = into / document.stem
        for index, (name, example) in enumerate(_EXAMPLE.findall(text)):
            write(folder / str(index) / (name or "robot.urdf"), example)
            for mesh_name, mesh in _MESH.findall(text):
                write(folder / str(index) / mesh_name, mesh)
    return into
