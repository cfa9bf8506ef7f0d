"""IN006 duplicated-element: a second element where URDF allows one, which the engines ignore."""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

from inertia_kit.analysis.links import LinkAnalysis
from inertia_kit.description import lines
from inertia_kit.description.edits import Edit, read_source
from inertia_kit.description.model import Duplicate, Source
from inertia_kit.errors import InputError
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.rules import RuleContext

if TYPE_CHECKING:
    # the markup scanner (a large regular expression) only to remove a duplicate
    from inertia_kit.description.xmlspan import Span

CODE = "IN006"
NAME = "duplicated-element"
SEVERITY = Severity.ERROR
SCOPE = "link"
# a second element where URDF allows one: MJCF's readers refuse what MuJoCo refuses
DESCRIPTION_FORMATS = ("urdf",)
SUMMARY = (
    "a second `<inertial>`, `<mass>`, `<inertia>`, `<origin>` or `<geometry>`, or a second shape "
    "in a `<geometry>`: the engines read the first and ignore it, MuJoCo refuses the file"
)
# removing a duplicate that is written exactly as the element the engines read changes nothing
# for urdfdom, Drake and PyBullet, and lets MuJoCo load the file
TEXT_FIX = Safety.SAFE

# differences named in the message, the weightiest first (the mass, then the tensor, then the
# centre of mass); the rest are counted there and listed in the detail and the help
SHOWN = 1
WEIGHT = ("shape", "mass", "inertia", "ixx", "iyy", "izz", "ixy", "ixz", "iyz", "origin", "xyz")


def _apart(read: Source, ignored: Source) -> tuple[Source, Source]:
    """
    Where the two differ: the elements themselves, or, when one macro body line made both
    (``<xacro:inertial_of m="2"/>`` called twice in a link), the innermost calls that differ.
    """
    pairs = [(read, ignored)]
    pairs += list(zip(reversed(read.calls), reversed(ignored.calls), strict=False))
    for a, b in pairs:
        if (a.path, a.line, a.column) != (b.path, b.line, b.column):
            return a, b
    return read, ignored


def _where(source: Source, other: Source) -> str:
    """``line 12`` in the same file as ``other`` (``line 12:40`` on the same line), else
    ``path:12``."""
    if source.path != other.path:
        return f"{source.path}:{source.line}"
    if source.line == other.line and source.column is not None:
        return f"line {source.line}:{source.column}"
    return f"line {source.line}"


def _near(source: Source, other: Source) -> str:
    """:func:`_where` for the message: a file other than ``other``'s by its name alone."""
    if source.path != other.path:
        return f"{source.path.replace(chr(92), '/').rsplit('/', 1)[-1]}:{source.line}"
    return _where(source, other)


def _engines(duplicate: Duplicate) -> str:
    """What each engine does with it (measured: see the rule's document)."""
    first = "urdfdom (ROS, Gazebo), Drake and PyBullet read the first and ignore this one silently"
    if duplicate.parent == "geometry" and duplicate.kind != "visual":
        return first.replace("urdfdom (ROS, Gazebo),", "urdfdom (ROS, Gazebo), MuJoCo,")
    if not _refused(duplicate):
        return first + "; MuJoCo's importer drops visuals"
    return first + f"; MuJoCo refuses the file (`XML Error: repeated element: '{duplicate.tag}'`)"


def _what(duplicate: Duplicate) -> str:
    if duplicate.parent == "geometry":
        return f"second shape `<{duplicate.tag}>` in `<geometry>`"
    holder = "" if duplicate.parent == "link" else f" in `<{duplicate.parent}>`"
    return f"second `<{duplicate.tag}>`{holder}"


def _weight(difference: tuple[str, str, str]) -> int:
    first = difference[0].split()[0]
    return WEIGHT.index(first) if first in WEIGHT else len(WEIGHT)


def _refused(duplicate: Duplicate) -> bool:
    """MuJoCo's schema refuses a repeated element; its importer drops visuals first."""
    return duplicate.parent != "geometry" and duplicate.kind != "visual"


def check(link: LinkAnalysis, ctx: RuleContext) -> Iterator[Finding]:
    for duplicate in link.link.duplicates:
        yield _finding(link.name, duplicate, ctx)


def _finding(name: str, duplicate: Duplicate, ctx: RuleContext) -> Finding:
    read, ignored = _apart(duplicate.read, duplicate.ignored)
    differences = [
        f"{what} {mine} vs {theirs}"
        for what, mine, theirs in sorted(duplicate.differences, key=_weight)
    ]
    if differences:
        shown = ", ".join(differences[:SHOWN])
        more = len(differences) - SHOWN
        says = f"they differ: {shown}" + (f" (+{more} more)" if more > 0 else "")
        every = f": they differ: {', '.join(differences)}" if more > 0 else ""
    else:
        says, every = "the same values", ""
    # a visual's duplicate changes no physics: what a person sees, and geometry-derived values
    # only where the link has no collision
    severity = Severity.ERROR if differences and duplicate.kind != "visual" else Severity.WARNING
    readers = "urdfdom, Drake and PyBullet" if _refused(duplicate) else "the engines"
    listed = "; ".join(differences) if differences else "none: both say the same"
    if differences:
        todo = (
            "decide which one is right (inertia-kit cannot tell: the author's intent is not "
            "written anywhere), keep it first or alone, and remove the other"
        )
    else:
        todo = "remove the duplicate: it changes nothing for the engines that load the file"
    return ctx.finding(
        f"link `{name}`: {_what(duplicate)} ({_near(ignored, read)}) ignored, {says}",
        duplicate.ignored,
        link=name,
        severity=severity,
        detail=f"the {_what(duplicate)} ({_where(ignored, read)}) is ignored, {readers} read "
        f"{_where(read, ignored)}{', MuJoCo refuses the file' if _refused(duplicate) else ''}"
        f"{every}",
        help=f"{_engines(duplicate)}. Read: {read}; ignored: {ignored}. Differences (read vs "
        f"ignored): {listed}. {todo[0].upper()}{todo[1:]}.",
        fixable=False,
        fix=None if differences else _removal(duplicate),
    )


def _removal(duplicate: Duplicate) -> Fix | None:
    """
    The edit that removes the ignored element (with its line when nothing else stands on it),
    only when it is written character for character as the one read (whitespace aside), both
    in the same file, in the same element and outside any macro: a macro body's duplicate may
    say the same for one call and differ for another, one inside an ``<xacro:if>`` may be the
    only one in another configuration, and a text that is not the one linted gets no edit.
    """
    read, ignored = duplicate.read, duplicate.ignored
    if read.calls or ignored.calls or read.path != ignored.path or None in (
        read.line, read.column, ignored.line, ignored.column,
    ):  # fmt: skip
        return None
    from inertia_kit.description.xmlspan import element_span

    try:
        source = read_source(ignored.path)
        text = source.text
        kept = element_span(text, source.offset(read.line, read.column))
        gone = element_span(text, source.offset(ignored.line, ignored.column))
    except (InputError, ValueError, IndexError):
        return None
    if (
        kept.tag != gone.tag
        or _words(text[kept.start : kept.end]) != _words(text[gone.start : gone.end])
        or not _siblings(text, kept, gone)
    ):
        return None
    start, end = gone.start, gone.end
    line_start = lines.line_start(text, start)
    rest = len(text) - len(text[end:].lstrip(" \t"))
    newline = next((n for n in ("\r\n", "\n", "\r") if text.startswith(n, rest)), "")
    if not text[line_start:start].strip() and (newline or rest == len(text)):
        start, end = line_start, rest + len(newline)  # the element alone on its line(s)
    return Fix(
        f"remove the duplicate <{duplicate.tag}>",
        (Edit(ignored.path, start, end, ""),),
        TEXT_FIX,
    )


def _siblings(text: str, first: Span, second: Span) -> bool:
    """
    Whether ``second`` follows ``first`` in the same element of the text: in xacro, not one
    of them inside an ``<xacro:if>`` the other is outside of (a configuration without the
    first would lose the element with the second).
    """
    from inertia_kit.description.xmlspan import tokens

    if second.start < first.end:
        return False
    depth = 0
    for token in tokens(text[first.end : second.start]):
        if token.group(1) is not None:  # an end tag
            depth -= 1
            if depth < 0:
                return False
        elif token.group(2) is not None and not token.group(4):  # a start tag, not empty
            depth += 1
    return depth == 0


def _words(text: str) -> list[str]:
    return text.split()
