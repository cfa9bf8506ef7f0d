"""
Shrinking a failing input: drop files, then delete chunks of lines (halves, quarters, ... down
to single lines), then attributes, while the same command still fails with the same signature.
Bounded by a number of attempts and a time budget; a run that hangs costs the time limit each
time, so a timeout or memory failure gets few attempts.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable

from fuzz.tree import WORK, Node, Tree

Fails = Callable[[Tree], bool]


def shrink(tree: Tree, fails: Fails, *, seconds: float, attempts: int) -> tuple[Tree, int]:
    """The smallest tree found that still ``fails``, and the attempts made."""
    deadline = time.monotonic() + seconds
    tried = 0

    def still(candidate: Tree) -> bool:
        nonlocal tried
        if tried >= attempts or time.monotonic() > deadline:
            raise _Spent
        tried += 1
        return fails(candidate)

    try:
        tree = _drop_nodes(tree, still)
        for key in _texts(tree):
            tree = _drop_chunks(tree, key, still, separator=b"\n")
        for key in _texts(tree):
            tree = _drop_attributes(tree, key, still)
    except _Spent:
        pass
    return tree, tried


class _Spent(Exception):
    pass


def _main_key(tree: Tree) -> str | None:
    return None if tree.main == "." else tree.key(tree.main)


def _drop_nodes(tree: Tree, still: Fails) -> Tree:
    main = _main_key(tree)
    for key in sorted(tree.nodes, key=lambda k: -k.count("/")):
        if key == main or key not in tree.nodes:
            continue
        candidate = tree.with_node(key, None)
        if still(candidate):
            tree = candidate
    return tree


def _texts(tree: Tree) -> list[str]:
    """Text files worth shrinking, the main one first."""
    main = _main_key(tree)
    keys = [
        k
        for k, n in tree.nodes.items()
        if n.kind == "file" and k.startswith(WORK + "/") and 0 < len(n.data) <= 4 << 20
    ]
    return sorted(keys, key=lambda k: (k != main, k))


def _drop_chunks(tree: Tree, key: str, still: Fails, separator: bytes) -> Tree:
    node = tree.nodes[key]
    pieces = node.data.split(separator)
    pieces = [p + separator for p in pieces[:-1]] + [pieces[-1]]
    size = max(len(pieces) // 2, 1)
    while size >= 1 and len(pieces) > 1:
        start = 0
        while start < len(pieces):
            kept = pieces[:start] + pieces[start + size :]
            candidate = tree.with_node(key, Node("file", b"".join(kept), mode=node.mode))
            if kept != pieces and still(candidate):
                pieces, tree = kept, candidate
            else:
                start += size
        size //= 2
    return tree


_ATTRIBUTE = re.compile(rb'\s+[\w:.-]+\s*=\s*(?:"[^"]*"|\'[^\']*\')')


def _drop_attributes(tree: Tree, key: str, still: Fails) -> Tree:
    node = tree.nodes[key]
    data = node.data
    at = 0
    while True:
        match = _ATTRIBUTE.search(data, at)
        if match is None:
            return tree
        shorter = data[: match.start()] + data[match.end() :]
        candidate = tree.with_node(key, Node("file", shorter, mode=node.mode))
        if still(candidate):
            data, tree = shorter, candidate
            at = match.start()
        else:
            at = match.end()
