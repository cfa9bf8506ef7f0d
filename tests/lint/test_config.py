"""Configuration: every key, validation errors that name the file and key, per-file globs."""

from __future__ import annotations

import pytest
from stub_rules import write

from inertia_kit.errors import ConfigError
from inertia_kit.lint.config import Config, LinkSettings, PerFileIgnore
from inertia_kit.lint.config_files import load_config
from inertia_kit.lint.findings import Severity

pytestmark = pytest.mark.usefixtures("stub_rules")

FULL = """
[project]
name = "x"

[tool.inertia-kit]
select = ["IN0", "in09"]
extend-select = ["stub-other"]
ignore = ["IN099"]
fail-on = "error"

[tool.inertia-kit.per-file-ignores]
"urdf/legacy/*.xacro" = ["IN098"]
"*.urdf" = ["stub-other"]

[tool.inertia-kit.rules.IN098]
severity = "error"
limit = 2
count = 4
strict = true
links = ["a", "b"]
mode = "b"

[tool.inertia-kit.rules.stub-other]
severity = "info"

[tool.inertia-kit.links.gripper]
density = 2700

[tool.inertia-kit.links."wheel link"]
mass = 0.25
"""


def test_every_key_of_pyproject(tmp_path):
    path = write(tmp_path / "pyproject.toml", FULL)
    config = load_config(path)
    base = str(tmp_path)
    assert config == Config(
        path=str(path),
        select=("IN0", "IN09"),
        extend_select=("stub-other",),
        ignore=("IN099",),
        per_file_ignores=(
            PerFileIgnore("urdf/legacy/*.xacro", base, ("IN098",)),
            PerFileIgnore("*.urdf", base, ("stub-other",)),
        ),
        fail_on=Severity.ERROR,
        options={
            "IN098": {"limit": 2.0, "count": 4, "strict": True, "links": ["a", "b"], "mode": "b"}
        },
        severities={"IN098": Severity.ERROR, "IN099": Severity.INFO},
        links={"gripper": LinkSettings(density=2700.0), "wheel link": LinkSettings(mass=0.25)},
    )
    assert isinstance(config.options["IN098"]["limit"], float)  # 2 in TOML is an integer


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "[tool.inertia-kit]\nselct = []\n",
            "`tool.inertia-kit.selct`: unknown key (did you mean `select`?); known here: "
            "`select`, `extend-select`, `ignore`, `per-file-ignores`, `fail-on`, `engines`, "
            "`rules`, `links`, `xacro`, `fix`, `unsafe-fixes`, `fixable`, `unfixable`, "
            "`exclude`, `extend-exclude`, `respect-gitignore`, `force-exclude`, "
            "`redact-environment`",
        ),
        (
            '[tool.inertia-kit]\nexclude = "build"\n',
            '`tool.inertia-kit.exclude`: expected a list of patterns, e.g. ["generated/"], '
            'got "build"',
        ),
        (
            "[tool.inertia-kit]\nrespect-gitignore = 1\n",
            "`tool.inertia-kit.respect-gitignore`: expected true or false, got 1",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nlimt = 1\n",
            "`tool.inertia-kit.rules.IN098.limt`: unknown key (did you mean `limit`?); known "
            "here: `severity`, `limit`, `count`, `strict`, `links`, `mode`",
        ),
        (
            "[tool.inertia-kit.links.arm]\ndensity = 1\nvolume = 2\n",
            "`tool.inertia-kit.links.arm.volume`: unknown key; known here: `density`, `mass`",
        ),
        (
            '[tool.inertia-kit]\nselect = "IN098"\n',
            '`tool.inertia-kit.select`: expected a list of codes or names, e.g. ["IN012"], '
            'got "IN098"',
        ),
        (
            '[tool.inertia-kit]\nignore = ["IN9"]\n',
            "`tool.inertia-kit.ignore`: `IN9` is not a rule code, code prefix or rule name",
        ),
        (
            '[tool.inertia-kit]\nselect = ["stub-hevy"]\n',
            "`tool.inertia-kit.select`: `stub-hevy` is not a rule code, code prefix or rule name "
            "(did you mean `stub-heavy`?)",
        ),
        (
            '[tool.inertia-kit.per-file-ignores]\n"*.urdf" = ["IN777"]\n',
            '`tool.inertia-kit.per-file-ignores."*.urdf"`: `IN777` is not a rule code, code prefix '
            "or rule name",
        ),
        (
            '[tool.inertia-kit]\nfail-on = "fatal"\n',
            '`tool.inertia-kit.fail-on`: expected "error", "warning" or "info", got "fatal"',
        ),
        (
            '[tool.inertia-kit.rules.IN098]\nseverity = "high"\n',
            '`tool.inertia-kit.rules.IN098.severity`: expected "error", "warning" or "info", '
            'got "high"',
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nlimit = true\n",
            "`tool.inertia-kit.rules.IN098.limit`: expected a number, got true",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nlimit = nan\n",
            "`tool.inertia-kit.rules.IN098.limit`: expected a number, got nan",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nlimit = -1\n",
            "`tool.inertia-kit.rules.IN098.limit`: expected a number from 0 up, got -1.0",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\ncount = 1.5\n",
            "`tool.inertia-kit.rules.IN098.count`: expected an integer, got 1.5",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nlinks = [1]\n",
            "`tool.inertia-kit.rules.IN098.links`: expected a list of strings, got a list",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\nstrict = 1\n",
            "`tool.inertia-kit.rules.IN098.strict`: expected true or false, got 1",
        ),
        (
            "[tool.inertia-kit.rules.IN999]\nseverity = 'error'\n",
            "`tool.inertia-kit.rules.IN999`: unknown rule: `IN999` is not a rule code, code prefix "
            "or rule name",
        ),
        (
            "[tool.inertia-kit.rules]\nIN098 = 3\n",
            "`tool.inertia-kit.rules.IN098`: expected a table, got 3",
        ),
        (
            "[tool.inertia-kit.rules.IN098]\n[tool.inertia-kit.rules.stub-heavy]\nlimit = 2\n",
            "`tool.inertia-kit.rules.stub-heavy`: IN098 (stub-heavy) is configured twice",
        ),
        (
            "[tool.inertia-kit.links.arm]\ndensity = 1\nmass = 2\n",
            "`tool.inertia-kit.links.arm`: give the link a density (kg/m³) or a mass (kg): "
            "exactly one",
        ),
        (
            "[tool.inertia-kit.links.arm]\n",
            "`tool.inertia-kit.links.arm`: give the link a density (kg/m³) or a mass (kg): "
            "exactly one",
        ),
        (
            "[tool.inertia-kit.links.arm]\nmass = -2\n",
            "`tool.inertia-kit.links.arm.mass`: expected a positive number from 1e-50 to 1e50, "
            "got -2",
        ),
        (
            "[tool.inertia-kit.links.arm]\ndensity = inf\n",
            "`tool.inertia-kit.links.arm.density`: expected a positive number from 1e-50 to 1e50, "
            "got inf",
        ),
        (
            "[tool.inertia-kit.links.arm]\ndensity = 1e-320\n",
            "`tool.inertia-kit.links.arm.density`: expected a positive number from 1e-50 to 1e50, "
            "got 1e-320",
        ),
        (
            '[tool.inertia-kit.per-file-ignores]\n" " = ["IN098"]\n',
            '`tool.inertia-kit.per-file-ignores." "`: an empty glob matches no file',
        ),
    ],
)
def test_bad_configuration_names_file_and_key(tmp_path, text, message):
    path = write(tmp_path / "pyproject.toml", text)
    with pytest.raises(ConfigError) as caught:
        load_config(path)
    assert str(caught.value) == f"{path}: {message}"


@pytest.mark.parametrize(
    ("pattern", "path", "matched"),
    [
        ("*.urdf", "robot.urdf", True),
        ("*.urdf", "deep/down/robot.urdf", True),  # no "/": a file name in any folder
        ("*.urdf", "robot.urdf.xacro", False),
        ("urdf/*.xacro", "urdf/arm.xacro", True),
        ("urdf/*.xacro", "urdf/sub/arm.xacro", False),
        ("urdf/*.xacro", "other/urdf/arm.xacro", False),  # relative to the config's folder
        ("urdf/**/*.xacro", "urdf/arm.xacro", True),
        ("urdf/**/*.xacro", "urdf/a/b/arm.xacro", True),
        ("**/legacy/*", "x/legacy/a.urdf", True),
        ("./urdf/arm.urdf", "urdf/arm.urdf", True),
        ("urdf/arm?.urdf", "urdf/arm2.urdf", True),
        ("urdf/arm[0-9].urdf", "urdf/arm7.urdf", True),
        ("urdf/arm[!0-9].urdf", "urdf/arm7.urdf", False),
        ("urdf/arm[!0-9].urdf", "urdf/armx.urdf", True),
        ("urdf/arm.urdf", "../outside/urdf/arm.urdf", False),
    ],
)
def test_per_file_ignore_globs(tmp_path, pattern, path, matched):
    project = tmp_path / "project"
    entry = PerFileIgnore(pattern, str(project), ("IN098",))
    assert entry.matches(project / path) is matched


def test_absolute_glob(tmp_path):
    entry = PerFileIgnore(f"{tmp_path.as_posix()}/*/robot.urdf", "/elsewhere", ("IN098",))
    assert entry.matches(tmp_path / "a" / "robot.urdf")
