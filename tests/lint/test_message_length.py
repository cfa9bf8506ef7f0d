"""
A finding's message is one line read at a glance (issue 21, item 5): the claim and its key
numbers, at most 120 characters with the link's name, as ``concise`` prints it; the basis, the
arithmetic, what each engine does and quotes are in its detail. Measured over every rule and
engine on the examples, and (slow) on the robot packages installed here.
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import json
from pathlib import Path

import pytest
from kit import EXAMPLES
from kit.in_process import run_split

from inertia_kit.cli.lint import lint_command

LONGEST = 120


def messages(folder: Path, *extra: str) -> list[dict]:
    code, stdout, _ = run_split(
        lint_command,
        ["--output-format", "json", "--exit-zero", "-q", "--engine", "all", *extra, str(folder)],
    )
    assert code == 0
    return json.loads(stdout)


def too_long(findings: list[dict]) -> list[str]:
    # IN000 is no finding but a file that could not be read: its message is the reader's own
    # error (xacro's, libxml2's), printed as `error:` on stderr, never on a concise line
    return [
        f"{f['code']} ({len(f['message'])}): {f['message']}"
        for f in findings
        if f["code"] != "IN000" and (len(f["message"]) > LONGEST or "\n" in f["message"])
    ]


def test_every_message_on_the_examples_is_one_short_line():
    findings = [f for folder in sorted(EXAMPLES.iterdir()) for f in messages(folder)]
    assert len({f["code"] for f in findings}) >= 8  # enough rules speak to measure
    assert too_long(findings) == []


def test_the_detail_keeps_what_the_message_leaves_out():
    """JSON still carries the numbers: the simple arm's IN062 says its declared and link-axes
    tensors in its detail (or expected)."""
    arm = EXAMPLES / "simple_arm"
    (finding, *_) = [f for f in messages(arm, "--select", "IN062") if f["link"] == "link_1"]
    carried = (finding["detail"] or "") + json.dumps(finding["expected"])
    for number in ("0.0076", "0.0002"):
        assert number in carried


def _installed_robot_folders() -> list[Path]:
    folders = []
    for module in ("pybullet_data", "rtbdata", "dexmate_urdf", "fourier_robot_descriptions"):
        spec = importlib.util.find_spec(module)
        if spec is not None and spec.submodule_search_locations:
            folders.append(Path(next(iter(spec.submodule_search_locations))))
    try:
        share = importlib.metadata.distribution("example-robot-data").locate_file(
            "cmeel.prefix/share/example-robot-data"
        )
        if Path(share).is_dir():
            folders.append(Path(share))
    except importlib.metadata.PackageNotFoundError:
        pass
    return folders


@pytest.mark.slow
@pytest.mark.parametrize("folder", _installed_robot_folders() or [None], ids=lambda f: str(f))
def test_every_message_on_the_installed_robot_packages_is_one_short_line(folder):
    if folder is None:
        pytest.skip("no robot package installed (pip install example-robot-data pybullet ...)")
    findings = messages(folder, "--package-path", str(folder), "-j", "2")
    assert too_long(findings) == []
