"""A centre of mass slip undone (analysis/forensics/com_slip): boxes, each slip planted."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from kit.urdf import box, collision, inertial, link, visual

from inertia_kit.analysis.forensics.com_slip import diagnose_com, link_frames, readings

#: a box well inside the positive octant, small against its distance from each axis plane: a
#: negated or exchanged coordinate of a point inside it lands far outside it
CENTRE = np.array([0.5, 0.3, 0.15])
HALF = np.array([0.08, 0.06, 0.04])


def _link(analysed, com, *, xyz=CENTRE, shapes=None):
    place = " ".join(str(v) for v in xyz)
    shapes = shapes or collision(box(*(2 * HALF)), xyz=place)
    body = inertial(1.0, 0.001, xyz=" ".join(repr(float(v)) for v in com)) + shapes
    return analysed(link("part", body)).by_name["part"]


def _diagnose(part, com):
    return diagnose_com(np.asarray(com, float), part.bases, link_frames(part.link, part.children))


TRUE = CENTRE + np.array([0.03, -0.02, 0.01])  # a third of the way out or less: a real part


@pytest.mark.parametrize(
    ("planted", "kind"),
    [
        (TRUE * [-1, 1, 1], "flip"),
        (TRUE * [1, -1, 1], "flip"),
        (TRUE * [1, 1, -1], "flip"),
        (-TRUE, "mirrored"),
        (TRUE[[1, 0, 2]], "swap"),
        (TRUE[[2, 1, 0]], "swap"),
        (TRUE[[0, 2, 1]], "swap"),
        (TRUE * 1000, "unit"),
    ],
)
def test_each_planted_slip_is_undone(analysed, planted, kind):
    part = _link(analysed, planted)
    found = _diagnose(part, planted)
    assert found is not None and found.reading is not None
    assert found.reading.kind == kind
    assert found.reading.point == pytest.approx(TRUE)
    assert found.declared_fraction > 1  # outside the box
    assert found.centroid_distance == pytest.approx(np.linalg.norm(TRUE - CENTRE))


def test_a_point_given_in_the_shape_frame_is_read_there(analysed):
    # the box's own origin is at CENTRE, turned a quarter about z: the point written relative
    # to it, in its axes
    quarter = "0 0 1.5707963267948966"
    shapes = collision(box(*(2 * HALF)), xyz=" ".join(map(str, CENTRE)), rpy=quarter)
    offset = TRUE - CENTRE
    local = np.array([offset[1], -offset[0], offset[2]])  # the same offset in the box's axes
    part = _link(analysed, local, shapes=shapes)
    found = _diagnose(part, local)
    assert found is not None and found.reading is not None
    assert found.reading.kind == "frame"
    assert "collision origin" in found.reading.words
    assert found.reading.point == pytest.approx(TRUE)


def test_the_same_point_read_two_ways_names_the_simpler(analysis_bar):
    # x = z = 0: y negated and every sign negated give the same point; the single flip speaks
    part, com = analysis_bar
    found = _diagnose(part, com)
    assert found is not None and found.reading is not None
    assert (found.reading.kind, found.reading.words) == ("flip", "y negated")


@pytest.fixture
def analysis_bar(analysed):
    shapes = collision(box(0.05, 0.4, 0.05), xyz="0 0.2 0") + visual(
        box(0.05, 0.4, 0.05), xyz="0 0.2 0"
    )
    com = np.array([0.0, -0.24, 0.0])
    return _link(analysed, com, xyz=(0, 0.2, 0), shapes=shapes), com


def test_two_readings_that_fit_alike_name_none(analysed):
    # a box centred on the z axis: z negated and every sign negated both land inside it,
    # at points equally far from its centroid
    com = np.array([0.03, 0.02, -0.3])
    shapes = collision(box(0.2, 0.2, 0.1), xyz="0 0 0.3")
    part = _link(analysed, com, xyz=(0, 0, 0.3), shapes=shapes)
    found = _diagnose(part, com)
    assert found is not None and found.reading is None
    assert {r.kind for r in found.rivals} == {"flip", "mirrored"}


def test_no_reading_when_nothing_lands_inside(analysed):
    com = np.array([2.0, 3.0, 4.0])  # far from the box whatever its signs or order
    assert _diagnose(_link(analysed, com), com) is None


def test_a_point_inside_or_at_the_origin_is_left_alone(analysed):
    assert _diagnose(_link(analysed, TRUE), TRUE) is None  # where real parts put it
    # left at the origin: no slip to undo (IN021 moves it to the centroid)
    assert _diagnose(_link(analysed, np.zeros(3)), np.zeros(3)) is None


def test_readings_skip_those_that_change_nothing():
    found = readings(np.array([0.0, 0.2, 0.0]))
    points = [tuple(r[3]) for r in found]
    assert (0.0, 0.2, 0.0) not in points  # x or z negated: the same point
    assert (0.0, -0.2, 0.0) in points


@settings(max_examples=40, deadline=None)
@given(
    inside=st.tuples(*[st.floats(-0.4, 0.4)] * 3),
    axis=st.integers(0, 2),
    pair=st.sampled_from([(0, 1), (0, 2), (1, 2)]),
    swap=st.booleans(),
)
def test_any_flip_or_swap_of_a_point_near_the_centroid_is_undone(
    tmp_path_factory, inside, axis, pair, swap
):
    from inertia_kit.analysis.links import analyse
    from inertia_kit.description.loader import load

    true = CENTRE + np.array(inside) * HALF  # at most 40 % of the way to each face
    planted = true.copy()
    if swap:
        planted[list(pair)] = true[list(pair[::-1])]
    else:
        planted[axis] = -true[axis]
    path = tmp_path_factory.mktemp("com") / "r.urdf"
    body = inertial(1.0, 0.001, xyz=" ".join(repr(float(v)) for v in planted))
    shapes = collision(box(*(2 * HALF)), xyz=" ".join(map(str, CENTRE)))
    path.write_text(f'<robot name="r">{link("part", body + shapes)}</robot>')
    part = analyse(load(path)).by_name["part"]
    found = _diagnose(part, planted)
    assert found is not None and found.reading is not None
    assert found.reading.point == pytest.approx(true)


def test_a_point_near_the_origin_is_not_read_as_millimetres(analysed):
    # a 4 cm part around the link origin, its centre of mass written 7 cm off it (Talos'
    # ankle links): read as millimetres it would land on the origin, inside, as any such
    # point would; millimetres are only read on a point far beyond the part
    com = np.array([-0.011, 0.047, 0.053])
    part = _link(analysed, com, xyz=(0, 0, 0.005), shapes=collision(box(0.04, 0.04, 0.04)))
    assert _diagnose(part, com) is None
