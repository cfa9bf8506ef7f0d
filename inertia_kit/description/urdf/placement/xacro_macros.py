"""
Reading a ``<xacro:macro>`` definition, as written: which macro holds an element, its parameters,
where its body uses them, and the name a call is written with.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from lxml import etree

_PARAMETER = re.compile(r"^\$\{\s*([A-Za-z_]\w*)\s*\}$")
_EXPRESSION = re.compile(r"\$\{([^}]*)\}")


def parameter_reference(text: str) -> str | None:
    """The name ``text`` refers to when it is exactly one ``${name}``, else ``None``."""
    found = _PARAMETER.match(text.strip())
    return None if found is None else found.group(1)


def child(element: etree._Element, name: str) -> etree._Element | None:
    """The first child element named ``name``."""
    return next((c for c in element if isinstance(c.tag, str) and c.tag == name), None)


def is_xacro(element: etree._Element, name: str) -> bool:
    from lxml import etree

    if not isinstance(element.tag, str):
        return False
    qname = etree.QName(element)
    return qname.localname == name and "xacro" in (qname.namespace or "")


def macro_of(element: etree._Element) -> etree._Element | None:
    """The ``<xacro:macro>`` whose body holds ``element`` directly (not inside another element)."""
    parent = element.getparent()
    while parent is not None and not is_xacro(parent, "macro"):
        if not (is_xacro(parent, "if") or is_xacro(parent, "unless")):
            return None
        parent = parent.getparent()
    return parent


def enclosing_macro(element: etree._Element) -> etree._Element | None:
    """The innermost ``<xacro:macro>`` holding ``element``."""
    parent = element.getparent()
    while parent is not None and not is_xacro(parent, "macro"):
        parent = parent.getparent()
    return parent


def written_name(element: etree._Element) -> str:
    """The tag as the file writes it: ``xacro:part`` (with its prefix), ``link``."""
    from lxml import etree

    local = etree.QName(element).localname
    return f"{element.prefix}:{local}" if element.prefix else local


# one parameter of ``params``, as xacro reads it: name, then ``:=`` or ``=`` and a default
# (``^`` forwards the caller's value; quotes keep spaces: ``xyz:='0 0 0'``)
_DEFAULT = r"""\$\{.*?\}|\$\(.*?\)|(?:'.*?'|".*?"|[^\s'"]+)+|"""
_WITH_DEFAULT = re.compile(
    r"^\s*([^\s:=]+?)\s*:?=\s*(\^\|?)?(" + _DEFAULT + r")(?:\s+|$)(.*)", re.S
)


def parameter_names(macro: etree._Element) -> dict[str, bool]:
    """``name -> has a default`` for a macro's ``params`` (blocks ``*x`` left out)."""
    names = {}
    rest = macro.get("params") or ""
    while rest.strip():
        found = _WITH_DEFAULT.match(rest)
        if found is not None:
            name, has_default, rest = found.group(1), True, found.group(4)
        else:
            name, _, rest = rest.strip().partition(" ")
            has_default = False
        if not name.startswith("*"):
            names[name.strip("^|")] = has_default
    return names


def uses(macro: etree._Element, name: str) -> int:
    """How many ``${...}`` expressions in the macro's attributes and text read ``name``."""
    word = re.compile(rf"\b{re.escape(name)}\b")
    count = 0
    for element in macro.iter():
        if element is macro or not isinstance(element.tag, str):
            continue
        texts = [*element.attrib.values(), element.text or "", element.tail or ""]
        for text in texts:
            count += sum(1 for e in _EXPRESSION.findall(text) if word.search(e))
    return count


def used_elsewhere(macro: etree._Element, parameter: str, mapped) -> bool:
    """Whether ``${...}`` expressions in the macro use ``parameter`` outside ``mapped``."""
    word = re.compile(rf"\b{re.escape(parameter)}\b")
    allowed = {(id(element), attribute) for element, attribute in mapped}
    for element in macro.iter():
        if element is macro or not isinstance(element.tag, str):
            continue
        texts = [
            value for name, value in element.attrib.items() if (id(element), name) not in allowed
        ]
        texts += [element.text or "", element.tail or ""]
        for text in texts:
            if any(word.search(expression) for expression in _EXPRESSION.findall(text)):
                return True
    return False
