"""IN002 non-positive-mass: a mass of zero or below, and the geometry's mass in its detail."""

from __future__ import annotations

import pytest
from kit.urdf import box, collision, inertial, joint, link, robot


def in002(lint, text: str):
    return [f for f in lint(text, "IN002") if f.code == "IN002"]


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    arm = link("arm", inertial(-1, 0.001) + collision(box(0.1, 0.1, 0.3)))
    (finding,) = in002(lint, robot(link("world"), joint("world", "arm", name="j"), arm))
    assert finding.message == "link `arm`: mass = -1 kg is not positive"
    assert len(finding.message) <= 100
    assert "its collision box (0.1 × 0.1 × 0.3 m) holds 0.003 m³" in finding.detail
    assert "3 kg at 1000 kg/m³" in finding.detail
    assert finding.expected["mass_at_1000_kg_m3"] == pytest.approx(3.0)


def test_without_geometry_there_is_no_basis(lint):
    arm = link("arm", inertial(0, 0.001))
    (finding,) = in002(lint, robot(link("world"), joint("world", "arm", name="j"), arm))
    assert finding.message == "link `arm`: mass = 0 kg is not positive"
    assert finding.detail is None and finding.expected is None
