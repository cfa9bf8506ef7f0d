"""
YAML files read through xacro (``${xacro.load_yaml('file.yaml')}``), bounded as the rest of an
expansion: the file is read only if it is a regular file of at most the robot-description bound
(50 MB), and its nodes are counted against the element limit, each alias as the nodes it stands
for, before anything is built from them.

An alias bomb (``b: &b [*a, *a, ...]``, nine levels of nine) is a few hundred bytes whose
aliases stand for 9⁹ nodes: PyYAML builds it sharing each list (cheap), and the first
expression that walks it (``str()``, a loop) runs into the memory limit after 7-12 s and 710 MB.
Counted on the composed node graph (each distinct node once, its expanded size remembered), it
is refused at once. An alias inside its own anchor (``&a [*a]``) stands for an endless
document: refused too.

:func:`hooked` installs the bounded ``load_yaml`` where xacro's expressions find it
(``xacro.load_yaml`` and the deprecated bare ``load_yaml``) for one expansion.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator
from typing import Any

from inertia_kit.description import safexml
from inertia_kit.description.xacro_limits import LimitExceeded, Meter, raise_hint
from inertia_kit.reading import read_regular

_DEPRECATED = "Using load_yaml() directly is deprecated. Use xacro.load_yaml() instead."


@contextlib.contextmanager
def hooked(xacro: Any, meter: Meter) -> Iterator[None]:
    """``load_yaml`` bounded by ``meter`` in xacro's expressions, restored afterwards."""
    symbols = xacro._global_symbols
    namespace = symbols["xacro"]
    saved = (dict.get(namespace, "load_yaml"), symbols.get("load_yaml"), xacro.load_yaml)

    def load_yaml(filename: str) -> Any:
        return _load(xacro, filename, meter)

    def deprecated(filename: str) -> Any:
        xacro.warning(_DEPRECATED)
        return load_yaml(filename)

    dict.__setitem__(namespace, "load_yaml", load_yaml)
    symbols["load_yaml"] = deprecated
    xacro.load_yaml = load_yaml
    try:
        yield
    finally:
        dict.__setitem__(namespace, "load_yaml", saved[0])
        symbols["load_yaml"] = saved[1]
        xacro.load_yaml = saved[2]


def _load(xacro: Any, filename: str, meter: Meter) -> Any:
    """What ``xacro.load_yaml`` returns, from the file read and counted within the bounds."""
    import yaml

    for unit in xacro.ConstructUnits:  # as xacro does: !radians, !degrees, !millimeters, ...
        yaml.SafeLoader.add_constructor(unit.value.tag, unit.constructor)
    path = xacro.abs_filename_spec(filename)
    data = read_regular(path, safexml.MAX_BYTES, filename, what="YAML file")
    xacro.filestack.append(path)
    try:
        loader = yaml.SafeLoader(data)
        try:
            node = loader.get_single_node()
            if node is None:
                return xacro.YamlListWrapper.wrap(None)
            _count(node, filename, meter)
            return xacro.YamlListWrapper.wrap(loader.construct_document(node))
        except RecursionError:  # PyYAML composes and builds recursively
            raise ValueError(
                f"the YAML file {filename} is nested deeper than PyYAML can read"
            ) from None
        finally:
            loader.dispose()
    finally:
        xacro.filestack.pop()
        xacro.all_includes.append(path)


def expanded_size(node: Any) -> int | None:
    """
    The nodes of the YAML node graph under ``node``, each alias counted as the nodes it stands
    for; ``None`` for an alias inside its own anchor (an endless document). Each distinct node
    is visited once (an explicit stack: nesting of any depth).
    """
    size: dict[int, int] = {}
    open_: set[int] = set()
    stack: list[tuple[Any, bool]] = [(node, False)]
    while stack:
        current, done = stack.pop()
        key = id(current)
        if done:
            open_.discard(key)
            size[key] = 1 + sum(size[id(child)] for child in _children(current))
            continue
        if key in size:
            continue
        if key in open_:
            return None
        open_.add(key)
        stack.append((current, True))
        for child in _children(current):
            if id(child) in open_:
                return None
            if id(child) not in size:
                stack.append((child, False))
    return size[id(node)]


def _children(node: Any) -> list[Any]:
    import yaml

    if isinstance(node, yaml.MappingNode):
        return [part for pair in node.value for part in pair]
    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    return []


def _count(node: Any, shown: str, meter: Meter) -> None:
    """Count ``node``'s expanded nodes against the element limit; ``LimitExceeded`` past it."""
    count = expanded_size(node)
    if count is None:
        raise LimitExceeded(
            f"the YAML file {shown} holds an alias inside its own anchor: it stands for an "
            "endless document"
        )
    limit = meter.limits.elements
    if limit and meter.elements + count > limit:
        raise LimitExceeded(
            f"the YAML file {shown} holds {count} nodes once its aliases are expanded, past "
            f"{meter.limits.describe('elements')}: an alias that stands for a list of aliases, "
            "level after level, multiplies the document",
            raise_hint("elements"),
        )
    meter.add(count)
