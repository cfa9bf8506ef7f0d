"""
Severity by consequence: a defect in a link's own values is judged also by the body engines
integrate, the lumped body of the links its fixed joints weld together.

A rule whose findings judge a link's own mass properties says so (``WEIGHED``, the rule
contract in :mod:`inertia_kit.lint.rules`). For such an error on a link that carries a
negligible share of its lumped body (:mod:`inertia_kit.engines.shares`: below 1 % of the mass
and of each principal moment, values every engine accepts as written), the runner lowers the
error and says the share:

- to a warning: the values are wrong, but cannot make the robot misbehave (Unitree Go1's 1e-5 kg
  camera frames with a 1e-6 kg·m² tensor on a 5.2 kg trunk);
- to info when the link adds nothing at all (``<mass value="0"/>`` with a zero tensor on a fixed
  frame): every engine loads it as it loads a link without ``<inertial>``, which no rule flags;
  it offers no fix then (``inertia-fill --fix invalid`` would give the frame its geometry's mass).

A body member whose own values are no real part's (:func:`~inertia_kit.analysis.fault.
implausible`: a tensor in kg·mm², a mass in grams) cannot vouch for a link's negligible share:
the link is judged again without such members and lowered only when negligible still. A
configured severity always wins; warnings are left as they are.
"""

from __future__ import annotations

import dataclasses

from inertia_kit.analysis.fault import implausible
from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.engines.shares import share
from inertia_kit.lint.findings import Finding, Severity


def weigh(robot: RobotAnalysis, finding: Finding) -> Finding | None:
    """
    ``finding``, lowered and with its link's share told when that share is negligible; ``None``
    for a massless body welded to the world in an MJCF model (``mass="0"`` with a zero tensor on
    a fixed mount: MuJoCo accepts it as written and never moves it, an idiom of its models).
    """
    if not finding.weighed or finding.severity is not Severity.ERROR or finding.link is None:
        return finding
    found = share(robot, finding.link)
    if found is None or not found.negligible:
        return finding
    # a massless frame adds nothing to any body; other values are judged also without the
    # members whose own values are in doubt
    if not found.massless and not _negligible_beside_real_parts(robot, finding.link):
        return finding
    # the share is the reason for the severity: the detail's first sentence
    detail = found.text() + (f"; {finding.detail}" if finding.detail else "")
    if found.massless and found.static and robot.robot.format == "mjcf":
        return None
    if found.massless:
        # a frame, as written: nothing to repair (`inertia-fill --fix invalid` leaves it)
        return dataclasses.replace(finding, severity=Severity.INFO, detail=detail, wants=None)
    return dataclasses.replace(finding, severity=Severity.WARNING, detail=detail)


def _negligible_beside_real_parts(robot: RobotAnalysis, name: str) -> bool:
    """
    Whether the link is negligible also in its body without the other members whose own values
    are no real part's (a tensor in kg·mm², a mass in grams: analysis.fault.implausible), which
    cannot vouch that anything beside them is negligible.
    """
    doubtful = robot.group_fact(
        name, "implausible", lambda g: frozenset(m.name for m in g if implausible(m))
    ) - {name}
    if not doubtful:
        return True
    alone = share(robot, name, leaving_out=doubtful)
    return alone is not None and alone.negligible
