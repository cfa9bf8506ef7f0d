"""
xacro's two tree edits, ``replace_node`` and ``remove_previous_comments``, with the same result
in time independent of the number of siblings, for :mod:`.xacro_session` to install.

xacro edits minidom trees through ``insertBefore`` and ``removeChild``, and minidom finds a
child by scanning its parent's list: each macro call at the top of a robot scans every element
made so far, five to eight times. A robot of 5000 macro calls spent 13 s in those scans (2000:
2.1 s), quadratic. Here a child is looked for first near where the last edit of its parent was
(xacro walks a parent's children in order, so the next one is a few places further), then by
the full scan; each move is one list splice.
"""

from __future__ import annotations

import itertools
from typing import Any
from xml.dom import HierarchyRequestErr, Node, NotFoundErr, minidom

#: ``id(parent.childNodes)`` -> the index of the last edit there. Only a hint: every index is
#: checked by identity, so a stale entry (a list collected, its id reused) costs a scan, no more.
_HINTS: dict[int, int] = {}
_NEAR = 24


def forget() -> None:
    """Drop the hints (at the end of an expansion)."""
    _HINTS.clear()


def replace_node(node: Any, by: Any, content_only: bool = False) -> None:
    """``xacro.replace_node``: ``by`` (a node or a list; with ``content_only``, their
    children) put where ``node`` is, and ``node`` removed."""
    parent = node.parentNode
    moved: list[Any] = []
    if by is not None:
        for doc in by if isinstance(by, list) else [by]:
            if content_only or doc.nodeType == Node.DOCUMENT_FRAGMENT_NODE:
                children = list(doc.childNodes)
                for child in children:
                    child.parentNode = None  # the whole list is moved: no scan for each
                del doc.childNodes[:]
                moved.extend(children)
            else:
                moved.append(doc)
    for child in moved:
        if child.nodeType not in parent._child_node_types:
            raise HierarchyRequestErr(f"{child!r} cannot be child of {parent!r}")
        if child.parentNode is not None:
            _remove(child.parentNode, child)
    index = _index(parent, node)
    before = parent.childNodes[index - 1] if index else None
    after = node.nextSibling
    parent.childNodes[index : index + 1] = moved
    chain = [before, *moved, after]
    for left, right in itertools.pairwise(chain):
        if left is not None:
            left.nextSibling = right
        if right is not None:
            right.previousSibling = left
    for child in moved:
        child.parentNode = parent
    node.parentNode = node.previousSibling = node.nextSibling = None
    _HINTS[id(parent.childNodes)] = index + len(moved)
    if node.nodeType in minidom._nodeTypes_with_children or any(
        child.nodeType in minidom._nodeTypes_with_children for child in moved
    ):
        minidom._clear_id_cache(parent)


def remove_previous_comments(node: Any) -> None:
    """``xacro.remove_previous_comments``: the comments right before ``node`` removed (over one
    blank line at most), and xacro's marker text node put after it."""
    import xacro

    following = node.nextSibling
    previous = node.previousSibling
    while previous:
        if (
            previous.nodeType == Node.TEXT_NODE
            and previous.data.isspace()
            and previous.data.count("\n") <= 1
        ):
            previous = previous.previousSibling
        if previous and previous.nodeType == Node.COMMENT_NODE:
            comment = previous
            previous = previous.previousSibling
            _remove(node.parentNode, comment)
        else:
            marker = xacro._empty_text_node
            if following and marker is not following:
                if marker.parentNode is not None:
                    _remove(marker.parentNode, marker)
                _insert_before(node.parentNode, marker, following)
            return


def _index(parent: Any, child: Any) -> int:
    children = parent.childNodes
    hint = _HINTS.get(id(children), 0)
    for index in range(max(hint - _NEAR, 0), min(hint + _NEAR, len(children))):
        if children[index] is child:
            return index
    try:
        return children.index(child)
    except ValueError:
        raise NotFoundErr() from None


def _remove(parent: Any, child: Any) -> None:
    index = _index(parent, child)
    del parent.childNodes[index]
    if child.nextSibling is not None:
        child.nextSibling.previousSibling = child.previousSibling
    if child.previousSibling is not None:
        child.previousSibling.nextSibling = child.nextSibling
    child.nextSibling = child.previousSibling = child.parentNode = None
    _HINTS[id(parent.childNodes)] = index
    if child.nodeType in minidom._nodeTypes_with_children:
        minidom._clear_id_cache(parent)


def _insert_before(parent: Any, child: Any, reference: Any) -> None:
    index = _index(parent, reference)
    parent.childNodes.insert(index, child)
    before = parent.childNodes[index - 1] if index else None
    child.previousSibling, child.nextSibling = before, reference
    reference.previousSibling = child
    if before is not None:
        before.nextSibling = child
    child.parentNode = parent
    _HINTS[id(parent.childNodes)] = index
    if child.nodeType in minidom._nodeTypes_with_children:
        minidom._clear_id_cache(parent)
