"""engines.vocabulary: engine names, verdicts, and how an event reads as a finding."""

from __future__ import annotations

import pytest

from inertia_kit.engines.vocabulary import (
    ENGINES,
    Event,
    Verdict,
    event,
    parse_engines,
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
        verdict_message("mujoco", Verdict.REFUSES, "inertia must satisfy A + B >= C")
        == "MuJoCo refuses the model: inertia must satisfy A + B >= C"
    )
    assert verdict_message("kdl", Verdict.CHANGES, None, "ignores the root's inertia") == (
        "KDL ignores the root's inertia"
    )
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
        "welds link `a`",
        "Converting unknown joint type",
        None,
        link="a",
        joint="free",
        joint_type="floating",
    )
    assert made == Event(
        "kdl",
        Verdict.CHANGES,
        "joint-type",
        "KDL welds link `a`: Converting unknown joint type",
        "Converting unknown joint type",
        None,
        "a",
        "free",
        {"joint_type": "floating"},
    )
    assert made.expected == {
        "engine": "kdl",
        "verdict": "changes",
        "engine_message": "Converting unknown joint type",
        "joint_type": "floating",
    }
