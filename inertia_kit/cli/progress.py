"""
A progress line on stderr while many files are linted: ``[=====     ] 12/40 robot.urdf``.

Shown only on a terminal, and only once the run has taken :data:`DELAY` seconds (a quick run
prints nothing extra); redrawn in place with a carriage return, and erased before anything
else is printed (:meth:`Progress.clear`), so that findings and the bar never share a line.
click's ``progressbar`` draws from the iteration of one loop and has no way to erase the bar
for output in between, hence this small one.
"""

from __future__ import annotations

import shutil
import sys
import time
from typing import TextIO

from inertia_kit.printable import printable

DELAY = 2.0  # seconds before the bar appears
WIDTH = 20  # characters of the bar itself


class Progress:
    """The bar for one run; a no-op when ``enabled`` is false."""

    def __init__(self, enabled: bool, stream: TextIO | None = None, delay: float = DELAY):
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.delay = delay
        self.start = time.monotonic()
        self.shown = False
        self.last = ""

    @classmethod
    def for_terminal(cls, quiet: bool) -> Progress:
        """A bar on stderr when it is a terminal and the run is not ``-q``."""
        isatty = getattr(sys.stderr, "isatty", lambda: False)
        return cls(not quiet and isatty())

    def update(self, done: int, total: int, current: str | None) -> None:
        """Draw ``done`` of ``total`` files, working on ``current``, once past the delay."""
        if not self.enabled or time.monotonic() - self.start < self.delay:
            return
        columns = shutil.get_terminal_size((80, 24)).columns
        filled = WIDTH * done // max(total, 1)
        line = f"[{'=' * filled}{' ' * (WIDTH - filled)}] {done}/{total}"
        if current:
            line += f" {printable(current)}"  # a file name may hold a CR or an escape
        line = line[: max(columns - 1, 10)]
        self.clear()
        self.stream.write(line)
        self.stream.flush()
        self.shown, self.last = True, line

    def clear(self) -> None:
        """Erase the bar (before other output); the next :meth:`update` draws it again."""
        if self.shown:
            self.stream.write("\r" + " " * len(self.last) + "\r")
            self.stream.flush()
            self.shown = False
