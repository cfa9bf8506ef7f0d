"""
One fuzz input as a folder tree, and what a run did to it.

An input is a :class:`Tree`: nodes keyed by their path below the run's root folder. ``work/`` is
the repository the commands run in (their current folder); ``outside/`` holds files beside it
that a planted link may point at (a script with its execute bit, a robot, a mesh), which no
command may ever change. A node is a file (bytes and mode), a symbolic link (its target, as
written), a FIFO, a folder (its mode: an unreadable folder), or a sparse file (``size`` bytes of
zeros after ``data``: a 4 GB file that costs nothing on disk).

:func:`snapshot` records a materialised tree (without following links, without opening FIFOs
or devices) so that two snapshots say which paths a run created, removed or changed.
"""

from __future__ import annotations

import base64
import hashlib
import json
import os
import stat
from collections.abc import Iterator
from dataclasses import dataclass, field, replace
from pathlib import Path

#: the folders of a run's root: the repository, what lies outside it, the caches, a home
WORK, OUTSIDE, CACHE, HOME = "work", "outside", "cache", "home"


@dataclass(frozen=True)
class Node:
    kind: str  # "file" | "link" | "fifo" | "dir" | "sparse"
    data: bytes = b""
    target: str = ""  # a link's target, as written (relative or absolute)
    mode: int | None = None  # None: the umask's default
    size: int = 0  # a sparse file's length

    def to_json(self) -> dict:
        out: dict = {"kind": self.kind}
        if self.data:
            out["data"] = base64.b64encode(self.data).decode("ascii")
        if self.target:
            out["target"] = self.target
        if self.mode is not None:
            out["mode"] = oct(self.mode)
        if self.size:
            out["size"] = self.size
        return out

    @classmethod
    def from_json(cls, raw: dict) -> Node:
        return cls(
            raw["kind"],
            base64.b64decode(raw.get("data", "")),
            raw.get("target", ""),
            int(raw["mode"], 8) if "mode" in raw else None,
            raw.get("size", 0),
        )


def file(data: bytes | str, mode: int | None = None) -> Node:
    return Node("file", data.encode("utf-8") if isinstance(data, str) else data, mode=mode)


def link(target: str) -> Node:
    return Node("link", target=target)


@dataclass
class Tree:
    """
    The files of one input. ``main`` is the robot file the commands are given (a path relative
    to ``work/``, or ``.`` for the whole folder); ``env`` what the environment adds (values a
    ``$(env)`` reads); ``notes`` how the input was made (generator and mutations, in order).
    """

    nodes: dict[str, Node] = field(default_factory=dict)
    main: str = "robot.urdf"
    env: dict[str, str] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    # --- building -------------------------------------------------------------------------

    def put(self, path: str, node: Node | bytes | str) -> None:
        """``node`` at ``work/path`` (``path`` may start with ``../outside/``)."""
        self.nodes[self.key(path)] = node if isinstance(node, Node) else file(node)

    @staticmethod
    def key(path: str) -> str:
        return os.path.normpath(os.path.join(WORK, path))

    def get(self, path: str) -> Node | None:
        return self.nodes.get(self.key(path))

    def work_files(self) -> list[str]:
        """The paths (relative to ``work/``) of the regular files in the repository."""
        prefix = WORK + "/"
        return sorted(
            k[len(prefix) :]
            for k, n in self.nodes.items()
            if k.startswith(prefix) and n.kind == "file"
        )

    def copy(self) -> Tree:
        return Tree(dict(self.nodes), self.main, dict(self.env), list(self.notes))

    def with_node(self, key: str, node: Node | None) -> Tree:
        """A copy with the node at root-relative ``key`` replaced (``None``: removed)."""
        out = self.copy()
        if node is None:
            out.nodes.pop(key, None)
        else:
            out.nodes[key] = replace(node)
        return out

    # --- on disk --------------------------------------------------------------------------

    def materialise(self, root: Path) -> None:
        """Write the tree below ``root`` (made, empty or missing), and the standard folders."""
        for folder in (WORK, OUTSIDE, CACHE, HOME):
            make_folders(root / folder)
        folders = []
        for key in sorted(self.nodes, key=lambda k: k.count("/")):
            node = self.nodes[key]
            path = root / key
            make_folders(path.parent)
            if node.kind == "dir":
                make_folders(path)
                folders.append((path, node.mode))
                continue
            if os.path.lexists(path):  # a later node over an earlier one's path
                if path.is_dir() and not path.is_symlink():
                    continue
                path.unlink()
            if node.kind == "file":
                path.write_bytes(node.data)
            elif node.kind == "sparse":
                with open(path, "wb") as stream:
                    stream.write(node.data)
                    stream.truncate(max(node.size, len(node.data)))
            elif node.kind == "link":
                os.symlink(node.target, path)
            elif node.kind == "fifo":
                os.mkfifo(path)
            if node.mode is not None and node.kind != "link":
                os.chmod(path, node.mode)
        for path, mode in reversed(folders):  # an unreadable folder last: its files are in
            if mode is not None:
                os.chmod(path, mode)

    # --- as data --------------------------------------------------------------------------

    def to_json(self) -> dict:
        return {
            "main": self.main,
            "env": self.env,
            "notes": self.notes,
            "nodes": {k: n.to_json() for k, n in sorted(self.nodes.items())},
        }

    @classmethod
    def from_json(cls, raw: dict) -> Tree:
        nodes = {k: Node.from_json(v) for k, v in raw["nodes"].items()}
        return cls(nodes, raw["main"], dict(raw.get("env", {})), list(raw.get("notes", [])))

    def size(self) -> int:
        """Bytes of content, a measure for the shrinker."""
        return sum(len(n.data) + len(n.target) + 1 for n in self.nodes.values())


def make_folders(path: Path) -> None:
    """``path`` and its missing parents, without recursion (Path.mkdir's: 1100 deep)."""
    missing = []
    while not os.path.isdir(path):
        missing.append(path)
        path = path.parent
    for folder in reversed(missing):
        os.mkdir(folder)


# --- snapshots -------------------------------------------------------------------------------

#: files larger than this are recorded by size and mtime, not by their hash
HASHED_BYTES = 64 << 20


@dataclass(frozen=True)
class Seen:
    kind: str  # "file" | "link" | "dir" | "fifo" | "other"
    mode: int
    digest: str = ""  # a file's content hash (or size:mtime for a huge one); a link's target
    size: int = 0


def entries(root: Path) -> Iterator[tuple[str, os.stat_result]]:
    """Every path below ``root`` and its lstat, without recursion (a folder may be 1100 deep)."""
    stack = [os.fspath(root)]
    while stack:
        folder = stack.pop()
        try:
            found = list(os.scandir(folder))
        except OSError:
            continue
        for entry in found:
            try:
                info = entry.stat(follow_symlinks=False)
            except OSError:
                continue
            yield entry.path, info
            if stat.S_ISDIR(info.st_mode):
                stack.append(entry.path)


def snapshot(root: Path) -> dict[str, Seen]:
    """Every path below ``root`` (relative), as seen without following a link or opening a FIFO."""
    return {os.path.relpath(path, root): _seen(path, info) for path, info in entries(root)}


def _seen(path: str, info: os.stat_result) -> Seen:
    mode = stat.S_IMODE(info.st_mode)
    if stat.S_ISLNK(info.st_mode):
        return Seen("link", 0, os.readlink(path))
    if stat.S_ISDIR(info.st_mode):
        return Seen("dir", mode)
    if stat.S_ISFIFO(info.st_mode):
        return Seen("fifo", mode)
    if not stat.S_ISREG(info.st_mode):
        return Seen("other", mode)
    if info.st_size > HASHED_BYTES:
        return Seen("file", mode, f"{info.st_size}:{info.st_mtime_ns}", info.st_size)
    digest = hashlib.blake2b(digest_size=16)
    with open(path, "rb") as stream:
        while chunk := stream.read(1 << 20):
            digest.update(chunk)
    return Seen("file", mode, digest.hexdigest(), info.st_size)


def changes(before: dict[str, Seen], after: dict[str, Seen]) -> dict[str, str]:
    """path -> "created" | "removed" | "changed" | "mode" (only its permission bits changed)."""
    out = {}
    for key in before.keys() | after.keys():
        old, new = before.get(key), after.get(key)
        if old == new:
            continue
        if old is None:
            out[key] = "created"
        elif new is None:
            out[key] = "removed"
        elif old.kind == new.kind and old.digest == new.digest and old.size == new.size:
            out[key] = "mode"
        else:
            out[key] = "changed"
    return out


def read_back(root: Path, key: str) -> bytes | None:
    """The bytes of the regular file at ``root/key`` (no link followed), or None."""
    path = root / key
    try:
        if not stat.S_ISREG(os.lstat(path).st_mode):
            return None
        return path.read_bytes()
    except OSError:
        return None


def dumps(tree: Tree) -> str:
    return json.dumps(tree.to_json(), indent=1, sort_keys=True)
