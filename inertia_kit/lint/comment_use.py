"""
What the suppression pass (:mod:`inertia_kit.lint.unused`) knows of one ``ignore[...]``
comment, and what a rule of scope ``"suppressions"`` (IN090) gets. Apart from the catalogue, so
that a rule can name it without importing every other rule.
"""

from __future__ import annotations

from dataclasses import dataclass, field


@dataclass
class CommentUse:
    """One ``ignore[...]`` comment: its selectors, those judged, those that covered a finding."""

    path: str
    line: int
    selectors: tuple[str, ...]
    lines: tuple[int, int]  # of the element it covers
    judged: set[str] = field(default_factory=set)
    used: set[str] = field(default_factory=set)
    robots: int = 1  # how many linted robots include its file
    # the digest of the bytes of its file as the load read them (description.reads; None:
    # unknown, or robots read different bytes): its removal is planned on those bytes only
    digest: str | None = None

    @property
    def unused(self) -> list[str]:
        """The judged selectors that suppressed nothing, in the order the comment gives them."""
        return [s for s in self.selectors if s in self.judged and s not in self.used]


# (path, line of the comment) -> its use
Uses = dict[tuple[str, int], CommentUse]
