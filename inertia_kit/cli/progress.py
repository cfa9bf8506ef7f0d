"""
A progress line on stderr while many files are linted: ``[=====     ] 12/40 robot.urdf``;
with ``rate`` (``inertia-kit scan``), also how fast and how long is left:
``[=====     ] 412/1000 61.2/s ETA 0:09 robot.urdf``.

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

    def __init__(
        self,
        enabled: bool,
        stream: TextIO | None = None,
        delay: float = DELAY,
        rate: bool = False,
    ):
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.delay = delay
        self.rate = rate
        self.start = time.monotonic()
        self.shown = False
        self.last = ""
        self.done_before = 0  # items done before this run (a resumed scan): not in the rate

    @classmethod
    def for_terminal(cls, quiet: bool, rate: bool = False) -> Progress:
        """A bar on stderr when it is a terminal and the run is not ``-q``."""
        isatty = getattr(sys.stderr, "isatty", lambda: False)
        return cls(not quiet and isatty(), rate=rate)

    def update(self, done: int, total: int, current: str | None) -> None:
        """Draw ``done`` of ``total`` files, working on ``current``, once past the delay."""
        if not self.enabled or time.monotonic() - self.start < self.delay:
            return
        columns = shutil.get_terminal_size((80, 24)).columns
        filled = WIDTH * done // max(total, 1)
        line = f"[{'=' * filled}{' ' * (WIDTH - filled)}] {done}/{total}"
        if self.rate:
            line += " " + rate_text(
                done - self.done_before, time.monotonic() - self.start, total - done
            )
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


def rate_text(done: int, seconds: float, left: int) -> str:
    """``61.2/s ETA 0:09``: items per second so far, and the time the ``left`` ones take at
    that rate (``ETA -`` before any is done)."""
    if done <= 0 or seconds <= 0:
        return "0.0/s ETA -"
    per_second = done / seconds
    return f"{per_second:.1f}/s ETA {_clock(left / per_second)}"


def _clock(seconds: float) -> str:
    """``0:09``, ``12:30``, ``3:05:00``."""
    whole = round(seconds)
    hours, rest = divmod(whole, 3600)
    minutes, secs = divmod(rest, 60)
    return f"{hours}:{minutes:02d}:{secs:02d}" if hours else f"{minutes}:{secs:02d}"
