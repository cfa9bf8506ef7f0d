"""Shared helpers of the analysis tests."""

from __future__ import annotations

import pytest

from inertia_kit.analysis.links import RobotAnalysis, analyse
from inertia_kit.description.loader import load


@pytest.fixture
def analysed(tmp_path):
    """``analysed(links, joints="")`` → the analysis of a robot made of those elements."""

    def build(links: str, joints: str = "") -> RobotAnalysis:
        path = tmp_path / "r.urdf"
        path.write_text(f'<robot name="r">{links}{joints}</robot>')
        return analyse(load(path))

    return build
