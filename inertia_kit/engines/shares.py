"""
What share of the body simulators integrate a welded link carries: the severity of a defect in a
link's own values follows from it.

Gazebo and MuJoCo merge a link on a fixed joint into its parent's body; Drake, PyBullet and KDL
weld it, which moves the welded links as one rigid body all the same. Either way what the
dynamics integrates is the lumped body: the sum of the group's declared mass properties
(:func:`~inertia_kit.engines.lumping.lumped`). A helper frame (an IMU, a camera mount, a contact
point) that declares 1e-5 kg on a 5 kg trunk changes that body's mass and moments by less than a
thousandth of a percent, so even an impossible tensor on it cannot make the robot misbehave.

The share is judged only on values every engine accepts as written, measured with MuJoCo 4,
Drake 1.51 and PyBullet 3.2.7 on a 1 kg body with a welded frame (rules/README.md, "Severity by
consequence"): a finite mass > 0 with a tensor Drake's ``CouldBePhysicallyValid`` accepts, or mass
0 with a zero tensor (a frame; every engine loads it as one). A negative mass or a tensor on a
massless frame is not: Drake replaces it by a 1 kg sphere and PyBullet's base drifts; a negative
moment MuJoCo refuses. Those keep their severity whatever their size.

Everything here is pure: it reads the analysis (declared values only) and returns values.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from inertia_kit.analysis.links import LinkAnalysis, RobotAnalysis
from inertia_kit.description.model import WORLD
from inertia_kit.engines.drake_reading import could_be_physically_valid
from inertia_kit.engines.lumping import lumped, lumped_without
from inertia_kit.physics.formatting import fmt
from inertia_kit.physics.mass import MassProperties, shift_tensor

#: below this share of the lumped body's mass and of each of its principal moments a link's
#: values change the body's accelerations under any force or torque by less than 1 %: less than
#: the spread of real parts about their CAD values (a factor 0.6-1.7, DESIGN.md) and the
#: weighing error of a real robot; the same 1 % IN013, IN021, IN022 and IN025 skip below
NEGLIGIBLE = 0.01


@dataclass(frozen=True)
class Share:
    """
    What one link's declared values weigh in the body its fixed joints weld it into.

    Attributes
    ----------
    link : str
      The link judged.
    body : str
      The link the engines name the lumped body after: the group's root, or the child of the
      moving joint that carries the group.
    body_mass : float
      The lumped body's mass, kg (the link's own included).
    mass : float
      The link's declared mass as a fraction of ``body_mass``.
    inertia : float
      The largest fraction the link adds to a principal moment of the lumped body about the
      body's centre of mass (its own tensor and its mass's parallel-axis term, along each
      principal axis of the body).
    static : bool
      The link is welded to the world, which engines never move (``body`` is ``world``, its
      mass infinite): told only for a massless frame.
    """

    link: str
    body: str
    body_mass: float
    mass: float
    inertia: float
    static: bool = False  # welded to the world: never integrated (then a massless frame only)

    @property
    def negligible(self) -> bool:
        return self.mass < NEGLIGIBLE and self.inertia < NEGLIGIBLE

    @property
    def massless(self) -> bool:
        """A frame: it adds nothing at all (mass 0 and a zero tensor, or no ``<inertial>``)."""
        return self.mass == 0 and self.inertia == 0

    def text(self) -> str:
        """``it adds 0.00018 % of the mass and 0.0055 % of the inertia of the body `base` …``"""
        body = (
            f"the body `{self.body}` it is welded into ({fmt(self.body_mass, 4)} kg), which is "
            "what every engine integrates"
        )
        frame = "engines load it as a frame without <inertial>"
        if self.static:
            return f"it is welded to the world, which engines never move: {frame}"
        if self.massless:
            return f"it adds nothing to {body}: {frame}"
        return (
            f"it adds {_percent(self.mass)} of the mass and {_percent(self.inertia)} of the "
            f"inertia of {body}"
        )


def _percent(fraction: float) -> str:
    return "0 %" if fraction == 0 else f"{fmt(100 * fraction, 2)} %"


def accepted_as_written(link: LinkAnalysis) -> MassProperties | None:
    """
    The link's declared values when every engine accepts them as written (see the module
    docstring): mass properties with mass > 0, or mass 0 with a zero tensor (then a zero
    :class:`MassProperties`); no ``<inertial>`` counts as mass 0. ``None`` otherwise.
    """
    if link.link.inertial is None:
        return MassProperties(0.0)
    declared = link.declared
    if declared is None or not math.isfinite(declared.mass) or declared.mass < 0:
        return None
    if not np.isfinite(declared.inertia).all() or not np.isfinite(declared.com).all():
        return None
    if declared.mass == 0:
        return MassProperties(0.0) if not declared.inertia.any() else None
    tensor = np.asarray(declared.inertia, dtype=np.float64)
    if not could_be_physically_valid(tensor) or float(np.linalg.eigvalsh(tensor)[0]) < 0:
        return None  # MuJoCo refuses a negative moment; Drake replaces an invalid tensor
    return declared


def _head(group: tuple[LinkAnalysis, ...]) -> LinkAnalysis:
    """The member the engines make the body of: the root, or the child of a moving joint."""
    return next((m for m in group if m.parent is None or m.parent.type != "fixed"), group[0])


def share(
    robot: RobotAnalysis, name: str, leaving_out: frozenset[str] = frozenset()
) -> Share | None:
    """
    The share of its lumped body the link ``name`` carries; ``None`` when there is no body to
    judge it by: the link is alone, its values are not accepted as written
    (:func:`accepted_as_written`), or the other links of its group carry no mass. A link welded
    to the world (never integrated) has a share only as a massless frame (``static``). The
    links ``leaving_out`` are left out of the body (members whose own values are in doubt).
    """
    link = robot.by_name.get(name)
    group = robot.group_of(name)
    if link is None or len(group) < 2 or name == WORLD:
        return None
    own = accepted_as_written(link)
    if robot.welded_to_world(name):
        # static: a massless frame there is a frame; other values are the rules' to judge
        if own is None or own.mass != 0:
            return None
        return Share(name, WORLD, math.inf, 0.0, 0.0, static=True)
    # in the link's frame, its own values included
    body = lumped_without(robot, name, leaving_out) if leaving_out else lumped(robot, name)
    if own is None or body is None or not body.mass - own.mass > 0:
        return None
    if not (math.isfinite(body.mass) and np.isfinite(body.inertia).all()):
        return None
    # what the link adds about the body's centre of mass, along each of its principal axes
    with np.errstate(all="ignore"):  # a value near the float range: inf, judged below
        added = np.asarray(own.inertia) + shift_tensor(own.mass, np.asarray(own.com) - body.com)
        moments, axes = np.linalg.eigh(np.asarray(body.inertia, dtype=np.float64))
        parts = [float(axes[:, k] @ added @ axes[:, k]) for k in range(3)]
    fractions = []
    for k, part in enumerate(parts):
        if not math.isfinite(part):
            fractions.append(math.inf)
        elif part <= 0:
            fractions.append(0.0)
        elif moments[k] > 0:
            fractions.append(part / float(moments[k]))
        else:
            fractions.append(math.inf)  # a body with no moment there: whatever it adds counts
    return Share(
        name, _head(group).name, body.mass, own.mass / body.mass, max(fractions, default=0.0)
    )
