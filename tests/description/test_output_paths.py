"""Which parts of an output path are looked at for symbolic links (description.output_paths)."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from inertia_kit.description.output_paths import link_on_the_way, refuse_links
from inertia_kit.errors import InputError


@pytest.fixture
def tree(tmp_path: Path, monkeypatch) -> Path:
    """The working folder ``work`` with a link ``out -> ../elsewhere`` and ``x -> y``."""
    work = tmp_path / "work"
    (work / "real").mkdir(parents=True)
    (tmp_path / "elsewhere").mkdir()
    (work / "out").symlink_to("../elsewhere")
    (work / "x").symlink_to("y")  # dangling: an output there would create y
    monkeypatch.chdir(work)
    return work


def test_the_file_itself_and_every_folder_on_a_relative_path(tree: Path):
    assert link_on_the_way("x") == ("x", "y", True)
    assert link_on_the_way("./x") == ("x", "y", True)
    assert link_on_the_way("out/report.sarif") == ("out", "../elsewhere", False)
    # `..` after a link climbs from where the link leads: the link is on the way
    assert link_on_the_way("out/../report.sarif") == ("out", "../elsewhere", False)
    assert link_on_the_way("real/report.sarif") is None
    assert link_on_the_way("report.sarif") is None


def test_an_absolute_path_below_the_working_folder_is_looked_at_below_it(tree: Path):
    assert link_on_the_way(tree / "out" / "r.sarif") == (str(tree / "out"), "../elsewhere", False)
    assert link_on_the_way(tree / "real" / "r.sarif") is None


def test_elsewhere_only_the_file_itself(tree: Path, tmp_path: Path):
    (tmp_path / "up").symlink_to("elsewhere")
    assert link_on_the_way(tmp_path / "up" / "r.sarif") is None
    (tmp_path / "elsewhere" / "r.sarif").symlink_to("/etc/passwd")
    found = link_on_the_way(tmp_path / "up" / "r.sarif")
    assert found == (str(tmp_path / "up" / "r.sarif"), "/etc/passwd", True)


def test_refused_unless_asked(tree: Path):
    with pytest.raises(InputError) as error:
        refuse_links("x", follow=False)
    assert (
        str(error.value)
        == "x: is a symbolic link to y: not written; --follow-symlinks writes through it"
    )
    refuse_links("x", follow=True)
    refuse_links("real/r.sarif", follow=False)
    assert os.path.islink("x")
