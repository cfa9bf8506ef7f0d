"""IN070 mujoco-verdict: the finding's wording (the real MuJoCo judges the predictions in
``tests/engines/test_mujoco_matrix.py``; these run without it)."""

from __future__ import annotations

from kit.urdf import inertial, joint, link, robot


def run(lint, text):
    return lint(text, select="IN070", engines=("mujoco",))


def test_runs_only_with_its_engine(lint):
    assert lint(robot(link("base"), joint("base", "arm"), link("arm")), select="IN070") == []


def test_refusal_is_one_short_line_and_the_detail_quotes_mujoco(lint):
    text = robot(link("base"), joint("base", "arm"), link("arm", inertial(0, 0.01)))
    (finding,) = run(lint, text)
    assert finding.severity.name == "ERROR" and finding.expected["first"] is True
    assert finding.message == "link `arm`: MuJoCo refuses the model: mass 0 kg, below mjMINVAL"
    assert len(finding.message) <= 100
    assert finding.detail == (
        "Link `arm` moves (joint `j_arm`) with mass 0 kg (below mjMINVAL = 1e-15 kg). "
        'MuJoCo says: "mass and inertia of moving bodies must be larger than mjMINVAL"'
    )
    assert finding.expected["engine_message"] in finding.detail


def test_silent_change_names_the_dropped_mass(lint):
    text = robot(
        link("base", inertial(2, 0.01)), joint("base", "arm"), link("arm", inertial(1, 0.01))
    )
    (finding,) = run(lint, text)
    assert finding.severity.name == "WARNING" and finding.expected["dropped_mass"] == 2.0
    assert finding.message == "link `base`: MuJoCo fixes the root to the world, dropping 2 kg"
    assert finding.detail == (
        "MuJoCo's URDF import adds no free joint: root link `base` is fixed to the world and "
        "the 2 kg of `base` are dropped."
    )
