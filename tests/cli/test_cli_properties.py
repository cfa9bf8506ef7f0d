"""
Property-based tests of the commands (hypothesis; the API's are in tests/test_properties.py):
for any URDF or xacro file (kit.generate), ``inertia-lint`` in every output format and with
every engine, ``inertia-kit report`` and ``inertia-fill`` exit 0, 1 or 2, never with a traceback
or an internal error; through click's runner, and as installed scripts in processes of their
own. Examples: the ``ci`` profile of tests/conftest.py, or INERTIA_KIT_HYPOTHESIS_EXAMPLES.
"""

from __future__ import annotations

import os
import subprocess
import tempfile
from pathlib import Path

from click.testing import CliRunner
from console_scripts import console_script
from hypothesis import given, settings
from hypothesis import strategies as st
from kit.generate import cases

from inertia_kit.cli import main

FORMATS = ("full", "concise", "json", "github", "sarif")


def _invoke(*args: str):
    result = CliRunner().invoke(main, list(args))
    assert result.exit_code in (0, 1, 2), (args, result.exit_code, result.output)
    assert "Traceback" not in result.output, (args, result.output)
    assert "internal error" not in result.output, (args, result.output)
    return result


@settings(max_examples=settings().max_examples // 4)
@given(cases(), st.sampled_from(FORMATS))
def test_commands_exit_0_1_or_2_without_a_traceback(case, output_format):
    with tempfile.TemporaryDirectory() as folder:
        path = str(case.write(Path(folder)))
        _invoke("lint", "--engine", "all", "--output-format", output_format, path)
        _invoke("report", path)
        _invoke("report", "--lumped", "--format", "json", path)
        _invoke("fill", "--fix", "all", "--diff", path)
        _invoke("fill", "--fix", "invalid", path)


@settings(max_examples=max(settings().max_examples // 50, 2))
@given(st.lists(cases(), min_size=1, max_size=8))
def test_console_scripts_exit_0_1_or_2_without_a_traceback(batch):
    """The installed scripts, in a process of their own, on a batch of cases."""
    with tempfile.TemporaryDirectory() as folder:
        paths = []
        for index, case in enumerate(batch):
            (Path(folder) / str(index)).mkdir()
            paths.append(str(case.write(Path(folder) / str(index))))
        for command in (["inertia-lint", "--engine", "all"], ["inertia-fill", "--diff"]):
            done = subprocess.run(
                [console_script(command[0]), *command[1:], *paths],
                capture_output=True,
                text=True,
                env=os.environ.copy(),
                timeout=300,
            )
            assert done.returncode in (0, 1, 2), done.stderr
            assert "Traceback" not in done.stderr + done.stdout, done.stderr
            assert "internal error" not in done.stderr, done.stderr
