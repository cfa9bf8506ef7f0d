"""engines.vocabulary: engine names, verdicts, and how an event reads as a finding."""

from __future__ import annotations

import pytest

from inertia_kit.engines.vocabulary import (
    ENGINES,
    Event,
    Verdict,
    event,
    parse_engines,
    verdict_detail,
    verdict_expected,
    verdict_message,
)


def test_parse_engines():
    assert parse_engines(["mujoco"]) == ("mujoco",)
    assert parse_engines(["kdl,MuJoCo", " gazebo "]) == ("mujoco", "gazebo", "kdl")
    assert parse_engines(["all"]) == ENGINES
    assert parse_engines(["mujoco,", ""]) == ("mujoco",)
    with pytest.raises(ValueError, match="unknown engine `bullet`; known: mujoco, gazebo, drake"):
        parse_engines(["mujoco,bullet"])


def test_verdict_vocabulary():
    assert (
        verdict_message("mujoco", Verdict.REFUSES, "mass 0 kg, below mjMINVAL", subject="link `a`")
        == "link `a`: MuJoCo refuses the model: mass 0 kg, below mjMINVAL"
    )
    assert verdict_message("kdl", Verdict.CHANGES, None, "ignores the root's inertia") == (
        "KDL ignores the root's inertia"
    )
    assert verdict_detail("kdl", "The root link is a name", "Use a dummy link.") == (
        'The root link is a name. KDL says: "Use a dummy link."'
    )
    assert verdict_detail("kdl", "Why.", None) == "Why."
    assert verdict_detail("kdl", None, None) is None
    assert verdict_expected("gazebo", Verdict.CHANGES, None, link_mass=1.0) == {
        "engine": "gazebo",
        "verdict": "changes",
        "engine_message": None,
        "link_mass": 1.0,
    }


def test_verdict_rank_orders_by_how_bad():
    assert Verdict.LOADS.rank < Verdict.CHANGES.rank < Verdict.REFUSES.rank


def test_event_reads_as_a_finding():
    made = event(
        "kdl",
        Verdict.CHANGES,
        "joint-type",
        "makes its floating joint fixed",
        "Converting unknown joint type",
        None,
        link="a",
        joint="free",
        why="KDL has no floating joint",
        joint_type="floating",
    )
    assert made == Event(
        "kdl",
        Verdict.CHANGES,
        "joint-type",
        "link `a`: KDL makes its floating joint fixed",
        "Converting unknown joint type",
        None,
        "a",
        "free",
        {"joint_type": "floating"},
        'KDL has no floating joint. KDL says: "Converting unknown joint type"',
    )
    assert made.expected == {
        "engine": "kdl",
        "verdict": "changes",
        "engine_message": "Converting unknown joint type",
        "joint_type": "floating",
    }
