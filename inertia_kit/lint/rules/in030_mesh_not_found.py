"""IN030 mesh-not-found: a ``<mesh filename>`` that does not resolve to a file."""

from __future__ import annotations

import os
from collections.abc import Iterator
from pathlib import Path

from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import model
from inertia_kit.description.package_files import (
    entry_is_dir,
    entry_is_file,
    exists,
    folder_entries,
    is_dir,
    is_file,
    package_name,
)
from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.rules import RuleContext

CODE = "IN030"
NAME = "mesh-not-found"
SEVERITY = Severity.ERROR
SCOPE = "link"
SUMMARY = "a visual/collision mesh URI does not resolve to a file"

PACKAGE = "package://"
# folders above the robot file searched for a package named by a URI that did not resolve
MAX_ANCESTORS = 8
# levels climbed from a place searched to the nearest existing folder, for a file of that name
MOVED_LEVELS = 3
# a URI longer than this is shortened in the message (its middle folders elided)
LONG_URI = 48


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for shape in (*link.link.visuals, *link.link.collisions):
        mesh = shape.geometry
        if not isinstance(mesh, model.Mesh) or mesh.path is not None:
            continue
        reason, advice = _split(mesh.problem or "the URI names no file")
        hint = _hint(mesh)
        searched = f"; searched {'; '.join(mesh.searched)}" if mesh.searched else ""
        expected = {"filename": mesh.filename, "kind": shape.kind, "searched": list(mesh.searched)}
        if hint:
            expected["found"] = hint[1]
        yield ctx.finding(
            f"link `{link.name}`: {shape.kind} mesh `{_shortened(mesh.filename)}` not found",
            mesh.source,
            link=link.name,
            expected=expected,
            detail=f"`{mesh.filename}`: {reason}{searched}",
            help=hint[0] if hint else advice,
        )


def _shortened(uri: str) -> str:
    """
    A URI longer than :data:`LONG_URI` with its middle folders elided, for the message:
    ``package://pkg/…/part.stl`` (the detail and ``expected`` have it whole).
    """
    if len(uri) <= LONG_URI:
        return uri
    scheme, sep, rest = uri.rpartition("://")
    head = f"{scheme}{sep}" if sep else ""
    parts = rest.split("/")
    first = next((i for i, p in enumerate(parts) if p), None)
    if first is None or first >= len(parts) - 2:
        return uri
    short = head + "/".join(parts[: first + 1]) + "/…/" + parts[-1]
    return short if len(short) < len(uri) else uri


def _split(problem: str) -> tuple[str, str]:
    """The resolver's problem as (why, what to do)."""
    reason, sep, advice = problem.partition(": pass ")
    if sep:
        return reason, "pass " + advice
    return problem, (
        "check the path (a relative path is relative to the file that names it), or name the "
        "file through its package (`package://pkg/...`) and pass --package-path DIR"
    )


def _hint(mesh: model.Mesh) -> tuple[str, str] | None:
    """
    Where the file probably is, with what to do: ``(help, path)``, or ``None``.

    Looks only at a few named places (a name that differs in case; a package folder next to
    the robot file or one of its ancestors), never a recursive search.
    """
    uri = mesh.filename.strip()
    base = Path(mesh.source.path).parent
    if uri.startswith(PACKAGE):
        rest = uri[len(PACKAGE) :]
        if rest.startswith("/"):
            fixed = PACKAGE + rest.lstrip("/")
            return (
                f"`package:///` names an empty package: write `{fixed}` (two slashes, then "
                "the package name)",
                fixed,
            )
        package, _, relative = rest.partition("/")
        if package and relative:
            return (
                _package_hint(package, relative, base)
                or _enclosing_hint(package, relative, base)
                or _moved_hint(mesh)
            )
        return None
    if "://" in uri:
        return None
    path = Path(uri[len("file://") :] if uri.startswith("file://") else uri)
    target = path if path.is_absolute() else base / path
    target = Path(os.path.normpath(target))
    variant = _case_variant(target)
    if variant is not None:
        return (
            f"`{variant}` exists: the name differs only in case (Windows and macOS ignore "
            "case, Linux and the simulators on it do not); write the name as it is on disk",
            str(variant),
        )
    similar = _similar(target)
    if similar is not None:
        return f"did you mean `{similar}`? It is in the same folder", str(similar)
    return _moved_hint(mesh)


def _enclosing_hint(package: str, relative: str, base: Path) -> tuple[str, str] | None:
    """The path after the package name exists in a folder above the file: another package."""

    for ancestor in [base, *base.parents][:MAX_ANCESTORS]:
        found = ancestor / relative
        if is_file(found):
            name = package_name(ancestor) or ancestor.name
            return (
                f"`{found}` exists, in `{ancestor}` above the robot file, but the URI names the "
                f"package `{package}`: write `package://{name}/{relative}` if that is the file, "
                f"or pass --package-path DIR with the `{package}` that holds it",
                str(found),
            )
    return None


def _moved_hint(mesh: model.Mesh) -> tuple[str, str] | None:
    """
    A file of the same name near a place searched: in the nearest existing folder on the way
    up (at most :data:`MOVED_LEVELS` levels) or one of its subfolders. One listing per folder.
    """
    for place in mesh.searched:
        expected = Path(place.rsplit(": ", 1)[-1])
        if not expected.is_absolute() or not expected.name:
            continue
        folder = expected.parent
        for _ in range(MOVED_LEVELS):
            if is_dir(folder):
                break
            folder = folder.parent
        else:
            continue
        found = _named_in(folder, expected.name)
        if found is not None:
            return (
                f"`{found}` exists, nearest to where the URI points (`{expected}`): the folders "
                "in the URI do not match the files on disk; correct the path",
                str(found),
            )
    return None


def _named_in(folder: Path, name: str) -> Path | None:
    """``folder/name`` or ``folder/*/name``, a file (first sorted), or ``None``."""
    if is_file(folder / name):
        return folder / name
    children = [e.path for e in folder_entries(folder) if entry_is_dir(e)]
    return next((Path(c) / name for c in children if is_file(Path(c) / name)), None)


def _similar(path: Path) -> Path | None:
    """A mesh file in the same folder with a close name (one listing, no recursion)."""
    import difflib  # a missing mesh only: not imported by every run

    names = [e.name for e in folder_entries(path.parent) if entry_is_file(e)]
    suffix = path.suffix.lower()
    candidates = [n for n in names if Path(n).suffix.lower() == suffix]
    close = difflib.get_close_matches(path.name, candidates, n=1, cutoff=0.7)
    return path.parent / close[0] if close else None


def _package_hint(package: str, relative: str, base: Path) -> tuple[str, str] | None:

    for ancestor in [base, *base.parents][:MAX_ANCESTORS]:
        candidates = [(ancestor / package, ancestor)]
        if ancestor.name == package:
            candidates.append((ancestor, ancestor.parent))
        for folder, holder in candidates:
            found = folder / relative
            if not is_file(found):
                variant = _case_variant(found)
                if variant is None:
                    continue
                found = variant
            declared = package_name(folder)
            if declared is not None and declared != package:
                return (
                    f"`{found}` exists, in the folder `{folder}` named after the package, but "
                    f"its package.xml names the package `{declared}`: write "
                    f"`package://{declared}/{relative}`, or rename the package",
                    str(found),
                )
            return (
                f"`{found}` exists: pass --package-path {holder} (PyBullet finds it by "
                "stripping `package://`; ROS, Gazebo and Drake need the package on their path)",
                str(found),
            )
    return None


def _case_variant(path: Path) -> Path | None:
    """An existing file whose path differs from ``path`` only in letter case, or ``None``."""
    parts = path.parts
    if not parts:
        return None
    current = Path(parts[0])
    for index, part in enumerate(parts[1:], start=1):
        exact = current / part
        if exists(exact):
            current = exact
            continue
        names = [e.name for e in folder_entries(current)]
        matches = [name for name in names if name.lower() == part.lower()]
        if len(matches) != 1:
            return None
        current = current / matches[0]
        if index < len(parts) - 1 and not is_dir(current):
            return None
    return current if is_file(current) and current != path else None
