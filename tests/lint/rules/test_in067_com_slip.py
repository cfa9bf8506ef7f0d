"""IN067 com-slip: a centre of mass off its geometry, its slip named; replaces IN021; its fix."""

from __future__ import annotations

import pytest
from kit.fixed_point import run_lint
from kit.urdf import box, collision, inertial, moving, visual

from inertia_kit.lint.findings import Repairs, Safety, Severity

BAR = collision(box(0.05, 0.4, 0.05), xyz="0 0.2 0") + visual(box(0.05, 0.4, 0.05), xyz="0 0.2 0")


def arm(xyz: str, shapes: str = BAR) -> str:
    return moving(inertial(2.0, 0.0271, 0.00083, 0.0271, xyz=xyz) + shapes)


def test_a_flipped_sign_is_named_and_replaces_in021(lint):
    findings = lint(arm("0.01 -0.24 0"))
    assert [f.code for f in findings] == ["IN067"]
    finding = findings[0]
    assert finding.severity == Severity.ERROR  # outside the hull, as IN021's error
    assert "with y negated it is inside, 41 mm from the geometry's centroid" in finding.detail
    assert finding.message == (
        "link `arm`: COM 0.24 m outside its geometry; with y negated, 41 mm from the centroid"
    )
    assert finding.expected["xyz"] == pytest.approx([0.01, 0.24, 0.0])
    assert finding.expected["hypothesis"] == "flip"
    assert finding.wants.safety == Safety.UNSAFE and finding.wants.repairs == Repairs.LIKELY


def test_inside_but_far_is_a_warning(lint):
    # a plate from y = -0.1 to 0.2: y = -0.06 is inside, 73 % of the way from its centroid
    # (y = 0.05) to its edge; negated, 10 mm from the centroid
    plate = collision(box(0.4, 0.3, 0.05), xyz="0.2 0.05 0")
    findings = lint(moving(inertial(2.0, 0.016, 0.027, 0.042, xyz="0.2 -0.06 0") + plate))
    assert [(f.code, f.severity) for f in findings] == [("IN067", Severity.WARNING)]
    message, detail = findings[0].message, findings[0].detail
    assert message == ("link `arm`: COM 73% to the edge; with y negated, 10 mm from the centroid")
    assert len(message) <= 100
    # the detail: the point, the geometry it is judged against, and the reading
    assert detail == (
        "the centre of mass (0.2, -0.06, 0) m lies 73% of the way from the centroid to the edge "
        "of its collision box (0.4 × 0.3 × 0.05 m); with y negated it is inside, 10 mm from "
        "the geometry's centroid"
    )


def test_a_long_name_leaves_the_distance_to_the_detail(lint):
    """The message keeps the slip and how far out the point is; with a link name of 40
    characters the corrected point's distance from the centroid is the detail's alone."""
    name = "hand_right_thumb_abduction_proximal_link"
    text = arm("0.01 -0.24 0").replace('"arm"', f'"{name}"')
    (finding,) = lint(text, "IN067")
    assert finding.message == f"link `{name}`: COM 0.24 m outside its geometry; with y negated"
    assert len(finding.message) <= 100
    assert "with y negated it is inside, 41 mm from the geometry's centroid" in finding.detail


def test_two_slips_alike_leave_in021(lint):
    # a box centred on the z axis: z negated or every sign negated fit as well
    shapes = collision(box(0.2, 0.2, 0.1), xyz="0 0 0.3")
    findings = lint(moving(inertial(2.0, 0.01, xyz="0.03 0.02 -0.3") + shapes))
    assert [f.code for f in findings] == ["IN021"]
    assert "with z negated or with every sign negated (mirrored) it would be inside alike" in (
        findings[0].help
    )


def test_the_fix_writes_the_corrected_point_and_is_a_fixed_point(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(arm("0.01 -0.24 0"))
    code, _ = run_lint(["--fix", "--unsafe-fixes", str(path)])
    assert code == 0
    text = path.read_text()
    assert '<origin xyz="0.01 0.24 0"/>' in text
    assert 'ixx="0.0271"' in text  # the tensor kept
    code, output = run_lint(["--fix", "--unsafe-fixes", str(path)])
    assert (code, output.strip()) == (0, "No findings in 1 file.")
    assert path.read_text() == text


def test_safe_fixes_alone_leave_it(tmp_path):
    path = tmp_path / "r.urdf"
    path.write_text(arm("0.01 -0.24 0"))
    before = path.read_text()
    run_lint(["--fix", str(path)])
    assert path.read_text() == before


def test_with_a_tensor_slip_both_are_undone_in_one_fix(tmp_path):
    # the tensor in kg·mm² (IN063) and the COM's y negated: one edit writes both corrections
    path = tmp_path / "r.urdf"
    path.write_text(moving(inertial(2.0, 27083.3, 833.3, 27083.3, xyz="0.01 -0.24 0") + BAR))
    run_lint(["--fix", "--unsafe-fixes", str(path)])
    text = path.read_text()
    assert '<origin xyz="0.01 0.24 0"/>' in text and 'ixx="0.0270833"' in text
    assert run_lint([str(path)])[1].strip() == "No findings in 1 file."


def test_a_safe_tensor_fix_is_not_held_back_by_the_unsafe_com_fix(tmp_path):
    # joined, the two made one unsafe fix: plain --fix took neither (IN063's safe one included)
    path = tmp_path / "r.urdf"
    path.write_text(moving(inertial(2.0, 27083.3, 833.3, 27083.3, xyz="0.01 -0.24 0") + BAR))
    code, output = run_lint(["--fix", str(path)])
    text = path.read_text()
    assert 'ixx="0.0270833"' in text and '<origin xyz="0.01 -0.24 0"/>' in text
    assert code == 1 and "Fixed 1 finding; 1 error remains" in output and "IN067" in output
    run_lint(["--fix", "--unsafe-fixes", str(path)])
    assert '<origin xyz="0.01 0.24 0"/>' in path.read_text()
    assert run_lint([str(path)])[1].strip() == "No findings in 1 file."
