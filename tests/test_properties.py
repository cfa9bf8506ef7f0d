"""
Property-based tests (hypothesis): for any URDF or xacro file (kit.generate: numbers over the
whole float range with NaN, inf and subnormals; missing, duplicated and unknown elements; odd
encodings; broken meshes), only ``InputError`` leaves the API (load, lint with every rule and
engine, every output format, report, fill planning and writing on a copy), and no numpy
overflow warning reaches the user. The commands: tests/cli/test_cli_properties.py.

CI runs a fixed, bounded set of examples (the ``ci`` profile in tests/conftest.py, about 40 s
in all); ``INERTIA_KIT_HYPOTHESIS_EXAMPLES=N`` runs N random examples per test instead::

    INERTIA_KIT_HYPOTHESIS_EXAMPLES=20000 python -m pytest -p no:cacheprovider \\
        tests/test_properties.py
"""

from __future__ import annotations

import contextlib
import json
import shutil
import tempfile
import warnings
from collections import Counter
from pathlib import Path

from hypothesis import event, given, settings
from kit.generate import Case, cases

from inertia_kit.engines.vocabulary import ENGINES
from inertia_kit.errors import InputError
from inertia_kit.lint.output import render
from inertia_kit.lint.runner import Selection, lint_file

FORMATS = ("full", "concise", "json", "github", "sarif")
EVERYTHING = Selection(select=("IN0",), engines=ENGINES)


def _numpy_warnings(caught: list[warnings.WarningMessage]) -> list[str]:
    """Overflow and invalid-value warnings: each would print a source line to the user."""
    return [f"{w.filename}:{w.lineno}: {w.message}" for w in caught if w.category is RuntimeWarning]


def _api(case: Case, folder: Path) -> None:
    from inertia_kit.description.loader import load
    from inertia_kit.fill.output import write_output
    from inertia_kit.fill.plan import apply, plan_fill
    from inertia_kit.report.robot import render as report
    from inertia_kit.report.robot import render_lumped

    path = case.write(folder)
    try:
        robot = load(path)
    except InputError as error:
        event(f"refused: {error.message.split(':')[0][:40]}")
        robot = None
    result = lint_file(path, EVERYTHING)
    for code in sorted({f.code for f in result.findings}):
        event(f"finding {code}")
    for output_format in FORMATS:
        errors = [result.error] if result.error is not None else []
        text = render(result.findings, output_format, errors=errors)
        if output_format in ("json", "sarif"):
            json.loads(text)
    if robot is not None and not robot.fragment:
        for output_format in ("text", "markdown", "json"):
            report(robot, output_format)
        for output_format in ("text", "markdown", "json"):
            render_lumped(robot, ENGINES, output_format)
    for fix in ("missing", "invalid", "all"):
        copy = folder / f"copy-{fix}"
        shutil.copytree(folder, copy, ignore=shutil.ignore_patterns("copy-*"))
        target = copy / case.main
        try:
            plan = plan_fill(target, fix=fix, density=1000.0)
            plan.diff()
            apply(plan)
        except InputError:
            continue
        event(f"fill {fix}: {len(plan.changed_links)} filled, {len(plan.refused)} refused")
        # what fill wrote loads again, and it wrote no number the linter refuses (IN004)
        assert robot is not None  # fill loaded it
        written = Counter((i.attribute, i.text) for i in load(target).invalid)
        assert written <= Counter((i.attribute, i.text) for i in robot.invalid), written
        if path.name.endswith(".xacro"):
            with contextlib.suppress(InputError):
                write_output(plan_fill(target, fix=fix, output=copy / "out.urdf"))


# half the profile's examples: each loads, lints, reports and fills a case three ways (the
# suite's longest test after the 5000-link ones); tests/fuzz feeds such inputs to the commands
@given(cases())
@settings(max_examples=settings().max_examples // 2)
def test_api_raises_only_input_errors(case):
    with (
        tempfile.TemporaryDirectory() as folder,
        warnings.catch_warnings(record=True) as caught,
    ):
        warnings.simplefilter("always")
        _api(case, Path(folder))
    assert _numpy_warnings(caught) == []
