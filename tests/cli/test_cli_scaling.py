"""
Every command linear in the number of links (issue 19): each command on robots of 5000 links
ends without an internal error within a generous bound, and takes at most 8 times the CPU time
it takes for 1000 links (linear: 5; the quadratic steps this found took 9 to 25 times, and a
welded chain did not end), or under 5 s of CPU. The rules (``lint --engine all``, from xacro: a
macro called once per link) and the commands that walk the tree (fill, report, view) run on a
serial chain (the deepest tree: no recursion may follow it) and on a star (the widest); the
commands that write into the text (``--add-noqa``, ``--fix``) on a star. ``python
benchmarks/scaling.py`` prints the figures of every command, shape and output format.
"""

from __future__ import annotations

import resource
from pathlib import Path

import pytest
from click.testing import CliRunner
from kit import write
from kit.big import XACRO_ELEMENTS, urdf, xacro
from kit.in_process import lint_in_process

from inertia_kit.cli import fill_main, lint_main, main

pytestmark = pytest.mark.slow

#: CPU seconds a command may take for 5000 links: generous (a loaded 2-vCPU VM takes 2 to 20)
BOUND = 90.0
#: the most CPU time 5000 links may take against 1000
RATIO = 8.0
#: ... unless 5000 links take less than this, CPU seconds: within a few seconds
FAST = 5.0

#: name -> (command, arguments): each run on a robot written for it; --diff and each output
#: format are measured by benchmarks/scaling.py (and the diff by tests/description)
COMMANDS = {
    "lint --engine all": (lint_main, ["--engine", "all", "--output-format", "json"]),
    "lint --fix --unsafe-fixes": (lint_main, ["--fix", "--unsafe-fixes", "-q"]),
    "lint --add-noqa": (lint_main, ["--add-noqa"]),
    "fill --fix all": (fill_main, ["--fix", "all"]),
    "report --lumped": (main, ["report", "--lumped"]),
    "view": (main, ["view", "-o", "{folder}/page.html"]),
}
CASES = [
    # the rules on both shapes, after an expansion: `--engine all` runs every rule and engine,
    # and the engines see the same 5000 links a URDF gives them
    *(("xacro", shape, "lint --engine all") for shape in ["chain", "star"]),
    # the commands that walk the tree themselves, on both shapes
    *(
        ("urdf", shape, name)
        for shape in ["chain", "star"]
        for name in ("fill --fix all", "report --lumped", "view")
    ),
    # the commands that write into the text: where a comment or a value goes is a matter of the
    # text, whatever the tree's shape, so one robot each (fewer runs keep CI within its time)
    ("urdf", "star", "lint --add-noqa"),
    # minified and half welded, in one robot: an element's column was counted from the start of
    # its line (the fuzz run, seed s1, input 5325), and with half the star welded to the base
    # every moving joint weighs a body of 2500 links against one (IN042 looked through the whole
    # welded body for each: 77 s of CPU at 5000 links, seed s1, input 13466)
    ("one-line-welded", "star", "lint --fix --unsafe-fixes"),
]


def one_line(links: int, shape: str, joint: str = "revolute") -> str:
    """:func:`kit.big.urdf` on one line after its declaration, as a minifier writes it."""
    declaration, rest = urdf(links, shape, joint=joint).split("\n", 1)
    return declaration + "\n" + rest.replace("\n", "") + "\n"


def one_line_welded(links: int, shape: str) -> str:
    return one_line(links, shape, joint="alternate")


MAKERS = {"urdf": urdf, "xacro": xacro, "one-line-welded": one_line_welded}
SUFFIXES = {"urdf": "urdf", "xacro": "xacro", "one-line-welded": "urdf"}


def cpu() -> float:
    """CPU seconds of this process and its children (xacro expands in a forked child)."""
    own = resource.getrusage(resource.RUSAGE_SELF)
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def run(command, arguments, robot: Path, folder: Path) -> float:
    arguments = [a.format(folder=folder) for a in arguments]
    if robot.suffix == ".xacro":
        arguments += ["--xacro-limit", f"elements={XACRO_ELEMENTS},timeout=0"]
    began = cpu()
    result = CliRunner().invoke(command, [*arguments, str(robot)])
    spent = cpu() - began
    assert result.exit_code in (0, 1), result.output[-2000:]
    assert "internal error" not in result.output
    return spent


@pytest.mark.parametrize(("kind", "shape", "name"), CASES)
def test_every_command_is_linear_in_the_links(tmp_path, monkeypatch, kind, shape, name):
    lint_in_process(monkeypatch)
    make = MAKERS[kind]
    command, arguments = COMMANDS[name]
    texts = {links: make(links, shape) for links in (1000, 5000)}

    def measure() -> dict[int, float]:  # each run on a fresh copy: --fix and fill write theirs
        robots = {
            n: write(tmp_path / f"{shape}{n}.{SUFFIXES[kind]}", text) for n, text in texts.items()
        }
        return {n: run(command, arguments, robot, tmp_path) for n, robot in robots.items()}

    spent = measure()
    assert spent[5000] < BOUND, spent
    for _ in range(2):
        if spent[5000] / spent[1000] < RATIO or spent[5000] < FAST:
            break
        # measured again, the lesser time of each size kept: a neighbour on the machine (the
        # other pytest-xdist worker) made 5000-link runs take 30-50 % longer than alone; a
        # quadratic step is as slow every time
        again = measure()
        spent = {n: min(spent[n], again[n]) for n in spent}
    # a command done within a few seconds of CPU at 5000 links is what the issue asks; its
    # 1000-link run (0.3 s, half of it the same setup whatever the size) is too short a base
    # to tell a ratio of 6 from 9 under a neighbour's load
    assert spent[5000] / spent[1000] < RATIO or spent[5000] < FAST, spent
