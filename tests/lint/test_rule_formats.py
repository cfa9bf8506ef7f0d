"""
Rules judge the formats they know (``DESCRIPTION_FORMATS``): what only URDF says or only
URDF's readers do stays silent on an MJCF model, and a rule that says nothing judges every
format.
"""

from __future__ import annotations

from inertia_kit.description.mjcf.reader import load_mjcf
from inertia_kit.lint import catalog
from inertia_kit.lint.runner import Selection, lint_robot

URDF_ONLY = {"IN005", "IN006", "IN024", "IN025", "IN040", "IN041", "IN050", "IN051"}
URDF_ENGINES = {"IN071", "IN072", "IN073", "IN074"}


def test_the_catalog_says_which_rules_judge_only_urdf():
    only = {rule.CODE for rule in catalog.RULES if catalog.formats(rule) == ("urdf",)}
    assert only == URDF_ONLY | URDF_ENGINES
    assert all(catalog.formats(rule) in (("urdf",), catalog.ALL_FORMATS) for rule in catalog.RULES)


def test_an_mjcf_hinge_without_range_is_no_urdf_joint_without_limit(tmp_path):
    path = tmp_path / "m.xml"
    path.write_text(
        '<mujoco><worldbody><body name="base"><geom type="box" size=".1 .1 .1"/>'
        '<body name="arm" pos="0 0 0.2"><joint name="j" type="hinge" axis="0 0 3"/>'
        '<inertial pos="0 0 0" mass="1" diaginertia="0.01 0.01 0.01"/>'
        '<geom type="box" size=".1 .1 .1" density="0"/></body></body></worldbody></mujoco>'
    )
    everything = Selection(("IN",), engines=("mujoco", "gazebo", "drake", "pybullet", "kdl"))
    codes = {finding.code for finding in lint_robot(load_mjcf(path), everything)}
    assert not codes & (URDF_ONLY | URDF_ENGINES)
