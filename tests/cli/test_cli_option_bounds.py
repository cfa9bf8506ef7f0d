"""A rule option's bounds, through the real command: a bad value is a configuration error."""

from __future__ import annotations

import pytest


@pytest.mark.parametrize("name", ["min_size", "max_size", "min_density", "max_density"])
def test_a_bound_on_a_log_scale_must_be_above_zero(name, tmp_path):
    """IN031 compares sizes and densities as logarithms: 0 is a configuration error (exit 2),
    not an internal error in the rule (fuzz s1, input 29728: math domain error)."""
    from click.testing import CliRunner

    from inertia_kit.cli.lint import lint_command

    (tmp_path / ".inertia-kit.toml").write_text(f"[rules.mesh-units]\n{name} = 0.0\n")
    robot = tmp_path / "r.urdf"
    robot.write_text('<robot name="r"><link name="a"/></robot>')
    result = CliRunner().invoke(lint_command, [str(robot)])
    assert result.exit_code == 2
    assert f"`rules.mesh-units.{name}`: expected a number above 0, got 0.0" in result.output
