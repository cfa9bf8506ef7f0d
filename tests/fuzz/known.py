"""
Failure classes the fuzz run finds and that are still open, each with where it is to be fixed:
the items of issue 19 (and the helper working on each), and what the fuzz run found beyond the
issue's list (reported, with a reproducer, to whoever merges). The CI test (test_fuzz.py) names
every failure it excuses by this list in a warning and fails on any other; whoever merges a fix
removes its entry, and the test then proves it gone (or fails on what is left).

Each entry: (class, a glob over the signature's detail, why it is excused).
"""

from __future__ import annotations

from fnmatch import fnmatchcase

ITEM_1 = "issue 19 item 1 (writers): edits applied only to the text they were computed on"
ITEM_2 = "issue 19 item 2: outputs and robot files never written through a planted link"
ITEM_3 = "issue 19 item 3 (printing): control characters escaped in every text output"
ITEM_4_CR = "issue 19 item 4 (robust): bare CR in the span and line mapping, --add-noqa placement"
ITEM_4_LINALG = "issue 19 item 4 (robust): Drake's LinAlgError on a 1e-300 moment"
ITEM_4_DEEP = "issue 19 item 4 (robust): no recursion on deep trees of links"
ITEM_4_LOOP = "issue 19 item 4 (robust): symlink loops in package walks"
ITEM_5 = (
    "issue 19 item 5 (robust): bounded reads and expansion results, bounded `full` excerpts, "
    "every command linear in links"
)
STDIN_FRAGMENT = (
    "found by the fuzz run, not in issue 19: `inertia-fill -` (and `inertia-lint --fix -`) "
    "writes the fixes that land in an included fragment into that file on disk"
)

KNOWN_OPEN: tuple[tuple[str, str, str], ...] = (
    # two writers at once: an end state no sequential order gives, a file that no longer parses,
    # or a writer that reads the other's half-done work
    ("concurrent-state", "*", ITEM_1),
    ("unparsable-write", "concurrent *", ITEM_1),
    ("internal-error", "* (concurrent)", ITEM_1),
    # -o through a link planted at the output; a robot file that links out of the repository
    ("write-outside", "*", ITEM_2),
    # raw CR, U+2028, NEL, ESC... from names, values, source lines and file names
    ("injection", "*", ITEM_3),
    ("internal-error", "ValueError at description/xmlspan.py:*", ITEM_4_CR),
    ("not-idempotent", "lint --add-noqa", ITEM_4_CR),
    ("internal-error", "*LinAlgError at engines/articulated.py:hinges", ITEM_4_LINALG),
    ("internal-error", "RecursionError at engines/mujoco*", ITEM_4_DEEP),
    ("internal-error", "OSError at description/package_files.py:*", ITEM_4_LOOP),
    # a 5000-link robot, a star, an 8 MB .gitignore line, a FIFO or /dev/zero read whole,
    # ${'x'*10**8} and a YAML bomb through xacro, 1 GB of `full` output
    ("timeout", "*", ITEM_5),
    ("memory", "*", ITEM_5),
    ("huge-output", "*", ITEM_5),
    ("changed-input", "fill - changed *.xacro", STDIN_FRAGMENT),
    ("changed-input", "lint --fix - changed *.xacro", STDIN_FRAGMENT),
)


def known_open(signature: str) -> str | None:
    """Why ``signature`` ("class: detail") is excused, or None."""
    kind, _, detail = signature.partition(": ")
    for known_kind, pattern, why in KNOWN_OPEN:
        if kind == known_kind and fnmatchcase(detail, pattern):
            return why
    return None
