"""
MJCF ``<default>`` classes as MuJoCo applies them: the top ``<default>`` is class ``main``,
each nested ``<default class>`` starts from its parent's values; an element takes its own
attribute, else its class's (its ``class``, else the ``childclass`` of the nearest body or
frame around it, else ``main``), else the parent classes'. The element a value comes from is
kept: a value written in a class is edited there.
"""

from __future__ import annotations

from collections.abc import Callable

from lxml import etree

from inertia_kit.description import model
from inertia_kit.errors import InputError

MAIN = "main"


def local(element: etree._Element) -> str | None:
    """An element's tag without its namespace; ``None`` for comments and instructions."""
    return etree.QName(element).localname if isinstance(element.tag, str) else None


class Defaults:
    """The default classes of one assembled model."""

    def __init__(self, root: etree._Element, source_of: Callable[[etree._Element], model.Source]):
        self.source_of = source_of
        # class -> its parent class (None for main); class -> tag -> the element setting it
        self.parents: dict[str, str | None] = {MAIN: None}
        self.elements: dict[str, dict[str, etree._Element]] = {MAIN: {}}
        for top in (c for c in root if local(c) == "default"):
            name = top.get("class", MAIN)
            if name != MAIN:
                source = source_of(top)
                raise InputError(
                    f"the top <default> is class `main`, not {name!r}",
                    source.path,
                    source.line,
                    source.column,
                )
            self._read(top, MAIN)

    def _read(self, element: etree._Element, name: str) -> None:
        for child in element:
            tag = local(child)
            if tag is None:
                continue
            if tag == "default":
                sub = child.get("class")
                if not sub or (sub in self.parents and self.parents[sub] != name):
                    source = self.source_of(child)
                    what = "has no class" if not sub else f"class {sub!r} is defined twice"
                    raise InputError(f"<default> {what}", source.path, source.line, source.column)
                self.parents[sub] = name
                self.elements.setdefault(sub, {})
                self._read(child, sub)
            else:
                self.elements[name][tag] = child

    def check(self, name: str, element: etree._Element) -> str:
        """``name`` if it is a class; else the ``InputError`` MuJoCo's ``unknown default class``
        is, located at ``element``."""
        if name not in self.parents:
            source = self.source_of(element)
            raise InputError(
                f"unknown default class {name!r}", source.path, source.line, source.column
            )
        return name

    def lookup(
        self, element: etree._Element, attribute: str, inherited: str
    ) -> tuple[str, etree._Element] | None:
        """
        ``(text, where)`` of ``attribute`` for ``element``: its own, else its class's chain
        (its ``class``, else ``inherited``: the childclass around it, ``main`` by default);
        ``None`` when nothing sets it.
        """
        text = element.get(attribute)
        if text is not None:
            return text, element
        tag = local(element)
        name: str | None = self.check(element.get("class", inherited), element)
        while name is not None:
            setting = self.elements[name].get(tag or "")
            if setting is not None and setting.get(attribute) is not None:
                return setting.get(attribute), setting
            name = self.parents[name]
        return None
