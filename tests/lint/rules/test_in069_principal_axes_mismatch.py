"""IN069 principal-axes-mismatch: principal axes turned beyond what a real part's scatter allows."""

from __future__ import annotations

import math

import numpy as np
import pytest
from kit.moments import box_tensor
from kit.urdf import box, collision, inertial, moving, visual

from inertia_kit.analysis.principal_axes import angle_limit
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.frames import rpy_matrix

SIZE = (0.5, 0.2, 0.1)
# a real part's moments: not the uniform box's (IN062 cannot undo a turn to within 10 %)
SCATTER = (1.3, 0.8, 0.9)


def turned(degrees: float, scatter=(1.0, 1.0, 1.0), flip: bool = False) -> str:
    """The box's tensor for 2 kg, its moments scaled by ``scatter``, turned about z."""
    moments = np.diag(box_tensor(2.0, SIZE)) * scatter
    turn = rpy_matrix((0.0, 0.0, math.radians(degrees)))
    t = turn @ np.diag(moments) @ turn.T
    sign = -1.0 if flip else 1.0
    return inertial(2.0, t[0, 0], t[1, 1], t[2, 2], ixy=sign * t[0, 1])


def in069(lint, text):
    return [f for f in lint(text) if f.code == "IN069"]


def test_a_part_turned_35_degrees(lint):
    findings = lint(moving(turned(35.0, SCATTER) + collision(box(*SIZE))))
    assert [f.code for f in findings] == ["IN069"]
    (finding,) = findings
    limit = finding.expected["limit"]
    assert finding.message == (
        f"link `arm`: axis of least inertia 35° from the geometry's (real parts ≤ {fmt(limit, 2)}°)"
    )
    assert len(finding.message) <= 100
    # the detail: both axes, the geometry, the spread of the moments and the limit it allows
    detail = finding.detail
    assert "axis of least inertia (0.819, 0.574, 0) is 35° from its collision box" in detail
    assert "(0.5 × 0.2 × 0.1 m)'s (1, 0, 0); with its moments apart by a factor of " in detail
    assert detail.endswith(f"a real part's axis strays at most {fmt(limit, 2)}°")
    assert finding.severity.name == "WARNING"
    assert finding.expected["rank"] == 0
    assert finding.expected["angle"] == pytest.approx(35.0, abs=1e-3)
    assert finding.expected["axis"] == pytest.approx([1.0, 0.0, 0.0])
    assert finding.expected["angle"] > finding.expected["limit"]


def test_axes_within_the_limit_or_aligned_are_fine(lint):
    least, middle, _ = np.diag(box_tensor(2.0, SIZE)) * SCATTER
    gap = math.log(middle / least)  # the declared least moment's, nearer than the box's
    within = angle_limit(gap) - 3.0
    assert in069(lint, moving(turned(0.0, SCATTER) + collision(box(*SIZE)))) == []
    assert in069(lint, moving(turned(within, SCATTER) + collision(box(*SIZE)))) == []


def test_a_cube_has_no_axes(lint):
    cube = box_tensor(2.0, (0.1, 0.1, 0.1))
    body = inertial(2.0, *np.diag(cube) * (1.1, 1.0, 0.95)) + collision(box(0.1, 0.1, 0.1))
    assert in069(lint, moving(body)) == []


def test_a_slip_the_forensics_name_is_theirs(lint):
    """The exact box turned (IN062) or with its product's sign flipped (IN061): one finding."""
    turned_box = moving(turned(30.0) + collision(box(*SIZE)))
    assert {f.code for f in lint(turned_box)} == {"IN062"}
    geometry = collision(box(*SIZE), rpy=(0.0, 0.0, math.radians(30.0)))
    assert {f.code for f in lint(moving(turned(30.0, flip=True) + geometry))} == {"IN061"}


def test_agreeing_with_the_visual_geometry_is_enough(lint):
    turned_visual = visual(box(*SIZE), rpy=(0.0, 0.0, math.radians(35.0)))
    body = turned(35.0, SCATTER) + collision(box(*SIZE)) + turned_visual
    assert in069(lint, moving(body)) == []
