"""
The rule catalog: an explicit registry of rule modules, and the context a rule checks with.

A rule is a module ``inN_<name>.py`` with a one-line docstring and::

    CODE = "IN020"                      # stable, never reused
    NAME = "inertia-geometry-mismatch"  # kebab-case, names the flagged pattern
    SEVERITY = Severity.WARNING         # default; configuration may change it
    SCOPE = "link"                      # "link": check(link: LinkAnalysis, ctx) per link;
                                        # "robot": check(robot: RobotAnalysis, ctx) once
    SUMMARY = "..."                     # one line for --statistics and the index
    OPTIONS = {"factor": float}         # option types ...
    DEFAULTS = {"factor": 2.0}          # ... and defaults
    def check(target, ctx: RuleContext) -> Iterator[Finding]: ...

Every rule has a document ``rules/<CODE>-<NAME>.md`` whose examples run as tests.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import ModuleType
from typing import Any

from inertia_kit.description.model import Source
from inertia_kit.lint.findings import Finding, Fix, Severity

# The registry, in code order. Adding a rule: write the module, add its name here, write its
# document in rules/.
RULE_MODULES: tuple[str, ...] = (
    "in001_missing_inertial",
    "in002_non_positive_mass",
    "in003_incomplete_inertial",
    "in004_invalid_number",
    "in010_inertia_not_positive_definite",
    "in011_inertia_triangle_inequality",
    "in012_inertia_too_small",
    "in013_placeholder_inertia",
    "in020_inertia_geometry_mismatch",
    "in021_com_geometry_mismatch",
    "in022_implausible_density",
    "in023_impossible_radius_of_gyration",
    "in024_visual_collision_mismatch",
    "in025_missing_collision",
    "in026_degenerate_geometry",
    "in030_mesh_not_found",
    "in031_mesh_units",
    "in032_mesh_not_watertight",
    "in033_mesh_inverted",
    "in034_mesh_unreadable",
    "in040_broken_tree",
    "in041_root_link_inertia",
    "in042_extreme_mass_ratio",
    "in050_joint_limits",
    "in051_joint_axis",
    "in060_inertia_about_other_point",
    "in061_product_signs_flipped",
    "in062_inertia_in_other_axes",
    "in063_inertia_unit_slip",
    "in064_inertia_attributes_transposed",
    "in070_mujoco_verdict",
    "in071_gazebo_verdict",
    "in072_drake_verdict",
    "in073_pybullet_verdict",
    "in074_kdl_verdict",
)


def load_rules(names: tuple[str, ...] = RULE_MODULES) -> tuple[ModuleType, ...]:
    """The rule modules, imported (rules whose module does not exist yet are skipped)."""
    rules = []
    for name in names:
        try:
            rules.append(importlib.import_module(f"inertia_kit.lint.rules.{name}"))
        except ModuleNotFoundError as error:
            if error.name != f"inertia_kit.lint.rules.{name}":
                raise
    return tuple(rules)


def by_code() -> dict[str, ModuleType]:
    return {rule.CODE: rule for rule in load_rules()}


@dataclass
class RuleContext:
    """What a rule's ``check`` gets besides its target: its options and a finding factory."""

    rule: ModuleType
    options: Mapping[str, Any] = field(default_factory=dict)
    severity: Severity | None = None  # configured override of the rule's default

    def option(self, name: str) -> Any:
        return self.options.get(name, self.rule.DEFAULTS[name])

    def finding(
        self,
        message: str,
        source: Source | None,
        *,
        link: str | None = None,
        joint: str | None = None,
        expected: dict[str, Any] | None = None,
        help: str | None = None,
        fix: Fix | None = None,
        severity: Severity | None = None,
    ) -> Finding:
        """
        A finding of this rule at ``source``. For an element a xacro macro produced, the
        location is the innermost macro call (what distinguishes this instance), and the
        element's place in the macro body is kept as ``macro_path``/``macro_line``.

        ``severity`` lets a rule escalate (e.g. warning → error for an impossible value); a
        configured severity always wins.
        """
        # Severity.INFO is 0: pick the first that is set, not the first that is truthy
        level = next(s for s in (self.severity, severity, self.rule.SEVERITY) if s is not None)
        path, line, column, macro_path, macro_line = "", None, None, None, None
        if source is not None:
            if source.calls:
                call = source.calls[-1]
                path, line, column = call.path, call.line, call.column
                macro_path, macro_line = source.path, source.line
            else:
                path, line, column = source.path, source.line, source.column
        return Finding(
            path,
            line,
            column,
            self.rule.CODE,
            self.rule.NAME,
            level,
            message,
            link=link,
            joint=joint,
            expected=expected,
            help=help,
            fix=fix,
            macro_path=macro_path,
            macro_line=macro_line,
        )
