"""
Runaway xacro through the commands (issue 11): ``${'x'*10**10}``, ``${10**10**10}`` and a
doubling macro chain exit 2 with a message naming the file, measured in time and memory; the
limits from ``[tool.inertia-kit.xacro]``, ``INERTIA_KIT_XACRO_LIMITS`` and ``--xacro-limit``.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest
from click.testing import CliRunner
from console_scripts import console_script
from kit import EXAMPLES, write
from kit.runaway_xacro import (
    EXPRESSION_LINE,
    HUGE_POWER,
    HUGE_STRING,
    doubling_chain,
    expression_robot,
)

from inertia_kit.cli import fill_main, lint_main, main
from inertia_kit.description.xacro_limits import ENV

#: Runs a command in a child process capped at 4 GB of address space (should a limit ever
#: fail, the test fails instead of the machine) and prints its exit code, wall seconds, peak
#: memory (MB, its children included) and stderr as JSON.
MEASURE = """
import json, resource, subprocess, sys, time
def cap():
    resource.setrlimit(resource.RLIMIT_AS, (4 << 30, resource.RLIM_INFINITY))
began = time.monotonic()
done = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=60, preexec_fn=cap)
seconds = time.monotonic() - began
peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
print(json.dumps([done.returncode, seconds, peak, done.stderr]))
"""

ROBOT = EXAMPLES / "my_robot_description" / "urdf" / "robot.xacro"


def measured(*args: str) -> tuple[int, float, float, str]:
    """Exit code, seconds, peak MB and stderr of ``inertia-lint ARGS``, run as a user runs it."""
    done = subprocess.run(
        [sys.executable, "-c", MEASURE, console_script("inertia-lint"), *args],
        capture_output=True,
        text=True,
        check=True,
    )
    code, seconds, megabytes, stderr = json.loads(done.stdout)
    return code, seconds, megabytes, stderr


def run(command, *args: str, env: dict[str, str] | None = None) -> tuple[int, str]:
    result = CliRunner().invoke(command, list(args), env=env, catch_exceptions=False)
    return result.exit_code, result.output


@pytest.fixture
def here(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    monkeypatch.delenv(ENV, raising=False)
    return tmp_path


# --- the reproducers, measured ----------------------------------------------------------------


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="measured with RLIMIT_AS")
@pytest.mark.parametrize(
    ("expr", "message"),
    [
        (HUGE_STRING, "xacro: 'x' * 10000000000 would be a string of 10000000000 characters"),
        (HUGE_POWER, "xacro: 10 ** 10000000000 would be an integer of 10000000001 digits"),
    ],
    ids=["string", "power"],
)
def test_runaway_expressions_exit_2_in_seconds_and_little_memory(here, expr, message):
    write(here / "robot.xacro", expression_robot(expr))
    code, seconds, megabytes, stderr = measured("robot.xacro")
    assert code == 2
    assert stderr.startswith(f"error: robot.xacro:{EXPRESSION_LINE}:3: {message}")
    assert "Traceback" not in stderr
    assert seconds < 10
    assert megabytes < 1024


def test_a_doubling_macro_chain_exits_2(here):
    write(here / "chain.xacro", doubling_chain())
    code, output = run(lint_main, "--xacro-limit", "elements=3000", "chain.xacro")
    assert code == 2
    assert "error: chain.xacro:" in output
    assert "xacro: the expansion made more than 3000 elements, the xacro element limit" in output


@pytest.mark.slow
@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="measured with RLIMIT_AS")
def test_the_doubling_chain_exits_2_within_the_default_limits(here):
    write(here / "chain.xacro", doubling_chain())
    code, seconds, megabytes, stderr = measured("chain.xacro")
    assert code == 2
    assert "xacro: the expansion made more than 50000 elements" in stderr
    assert seconds < 30 and megabytes < 1024


@pytest.mark.parametrize(
    "command",
    [
        (fill_main,),
        (fill_main, "-o", "out.urdf"),
        (main, "report"),
        (main, "lint"),
    ],
    ids=["fill", "fill-o", "report", "lint"],
)
def test_every_command_refuses_with_the_message(here, command):
    write(here / "robot.xacro", expression_robot(HUGE_POWER))
    command, *args = command
    code, output = run(command, *args, "robot.xacro")
    assert code == 2
    assert f"robot.xacro:{EXPRESSION_LINE}:3: xacro: 10 ** 10000000000 would be" in output
    assert not (here / "out.urdf").exists()


# --- where the limits come from ---------------------------------------------------------------


def test_the_configuration_environment_and_command_line_set_the_limits(here):
    write(here / "robot.xacro", ROBOT.read_text())
    for name in ("base.xacro", "macros.xacro", "wheels.xacro", "sensors.xacro"):
        write(here / name, (ROBOT.parent / name).read_text())
    assert run(lint_main, "--exit-zero", "robot.xacro")[0] == 0
    write(here / "pyproject.toml", "[tool.inertia-kit.xacro]\nelements = 10\n")
    code, output = run(lint_main, "robot.xacro")
    assert code == 2
    assert "the expansion made more than 10 elements, the xacro element limit (10" in output
    # the environment over the configuration, the command line over both
    assert run(lint_main, "--exit-zero", "robot.xacro", env={ENV: "elements=0"})[0] == 0
    code, output = run(
        lint_main, "--xacro-limit", "elements=20", "robot.xacro", env={ENV: "elements=0"}
    )
    assert (code, "more than 20 elements" in output) == (2, True)
    # fill and report read the same configuration
    for command, *args in ((fill_main, "--check"), (main, "report")):
        code, output = run(command, *args, "robot.xacro")
        assert (code, "more than 10 elements" in output) == (2, True)


@pytest.mark.parametrize(
    ("table", "message"),
    [
        ("timeout = -1", "`tool.inertia-kit.xacro.timeout`: `timeout` takes a number of s ≥ 0"),
        ('memory = "1 GB"', "`tool.inertia-kit.xacro.memory`: expected a number (0: no limit)"),
        ("elements = 2.5", "`tool.inertia-kit.xacro.elements`: `elements` takes a whole number"),
        ("time = 3", "`tool.inertia-kit.xacro.time`: unknown key (did you mean `timeout`?)"),
    ],
)
def test_bad_configured_limits_exit_2(here, table, message):
    write(here / "r.xacro", expression_robot("1"))
    write(here / "pyproject.toml", f"[tool.inertia-kit.xacro]\n{table}\n")
    code, output = run(lint_main, "r.xacro")
    assert code == 2
    assert output.startswith(f"error: {here / 'pyproject.toml'}: {message}")


@pytest.mark.parametrize("command", [lint_main, fill_main, main], ids=["lint", "fill", "report"])
def test_bad_limits_on_the_command_line_or_in_the_environment_exit_2(here, command):
    write(here / "r.xacro", expression_robot("1"))
    prefix = ("report",) if command is main else ()
    code, output = run(command, *prefix, "--xacro-limit", "memory=lots", "r.xacro")
    assert code == 2
    assert output == "error: --xacro-limit: `memory` takes a number of MB, got 'lots'\n"
    code, output = run(command, *prefix, "r.xacro", env={ENV: "timeout"})
    assert code == 2
    assert output.startswith(f"error: {ENV}='timeout': expected NAME=VALUE (timeout=SECONDS")


def test_the_option_is_documented_in_help():
    output = run(lint_main, "--help")[1]
    assert "--xacro-limit NAME=VALUE" in output
    assert "timeout=SECONDS (default 30), memory=MB (1024) or elements=COUNT (50000)" in " ".join(
        output.split()
    )


def test_a_real_robot_lints_within_the_defaults(here):
    code, output = run(lint_main, "--exit-zero", str(ROBOT))
    assert code == 0 and not output.startswith("error:") and "\nerror:" not in output


def test_the_example_folder_lints_within_the_defaults(here):
    code, output = run(lint_main, "--exit-zero", str(EXAMPLES))
    assert code == 0 and "could not be read" not in output
