"""
What MuJoCo's URDF import and compiler (``mujoco.MjModel.from_xml_path``) do with each link,
predicted from our model alone: the refusals in the order MuJoCo meets them (it reports only the
first), then the silent changes. The sources are in ``rules/IN070-mujoco-verdict.md``;
``tests/engines/test_mujoco_matrix.py`` checks every prediction against the real ``mujoco``.

MuJoCo reads the files (:mod:`.mujoco_files`: the parser's ``<inertial>`` errors, the collision
meshes), then compiles the bodies (:mod:`.mujoco_compiler`: each body's inertia and geoms, the
fusion of welded links, the last check on moving bodies); this module puts their predictions in
MuJoCo's order and words them as events.
"""

from __future__ import annotations

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.mujoco_compiler import compile_robot
from inertia_kit.engines.mujoco_files import Prediction, mesh_refusals, parse_refusals
from inertia_kit.engines.vocabulary import (
    Event,
    Verdict,
    subject_of,
    verdict_detail,
    verdict_message,
)

ENGINE = "mujoco"


def events(robot: RobotAnalysis) -> list[Event]:
    """
    What MuJoCo does with the robot, as events of kind ``stage`` (see
    :class:`~.mujoco_files.Prediction`): the first refusal reads ``link `x`: MuJoCo refuses the
    model: <claim>``, the later ones ``MuJoCo would also refuse the model`` (what it says once
    the first is fixed); a silent change reads ``link `x`: MuJoCo <claim>``. The detail says why
    and quotes MuJoCo. Empty: the model loads as written.
    """
    predictions = predict(robot)
    first = next((p for p in predictions if p.verdict is Verdict.REFUSES), None)
    return [_event(prediction, first) for prediction in predictions]


def _event(prediction: Prediction, first: Prediction | None) -> Event:
    subject = subject_of(prediction.link)
    why = prediction.detail
    if prediction.verdict is Verdict.REFUSES:
        assert first is not None
        what = "refuses the model"
        if prediction is not first:
            what = "would also refuse the model"
            place = f"link `{first.link}`" if first.link else "the first"
            why = f"{why}; MuJoCo stops at the first error, {place}, and says this once it is fixed"
        message = verdict_message(
            ENGINE, prediction.verdict, prediction.claim, what, subject=subject
        )
    else:
        message = verdict_message(
            ENGINE, prediction.verdict, None, prediction.claim, subject=subject
        )
    return Event(
        ENGINE,
        prediction.verdict,
        prediction.stage,
        message,
        prediction.message,
        prediction.source,
        link=prediction.link,
        facts={
            "stage": prediction.stage,
            "engine_element": prediction.element,
            "first": prediction is first,
            **prediction.more,
        },
        detail=verdict_detail(ENGINE, why, prediction.message),
    )


def predict(robot: RobotAnalysis) -> list[Prediction]:
    """
    The refusals in the order MuJoCo meets them, then the silent changes. Robots whose tree
    MuJoCo's importer cannot build (IN040) get no prediction; an MJCF model's are its
    compiler's (:mod:`.mujoco_inference`).
    """
    if robot.robot.format == "mjcf":
        from inertia_kit.engines.mujoco_inference import predictions

        return predictions(robot)
    compiled = compile_robot(robot)
    if compiled is None:
        return []
    refusals, changes = compiled
    refusals = parse_refusals(robot) + mesh_refusals(robot) + refusals
    if any(r.stage == "parse" for r in refusals):
        changes = []  # nothing past the parser is certain
    return refusals + changes
