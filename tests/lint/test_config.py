"""Configuration: discovery, every key, validation errors that name the file and key."""

from __future__ import annotations

import types
from pathlib import Path

import pytest
from kit import write
from kit.urdf import joint_lines, link_lines, robot_lines

from inertia_kit.errors import ConfigError
from inertia_kit.lint import config as config_module
from inertia_kit.lint import rules as registry
from inertia_kit.lint.config import (
    Config,
    ConfigFinder,
    LinkSettings,
    PerFileIgnore,
    find_config,
    load_config,
)
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.runner import Selection, lint_paths, selection_for

ROBOT = robot_lines(link_lines("base"), joint_lines("base", "arm"), link_lines("arm", 3, 0.001))


def _rule(code: str, name: str, options: dict, defaults: dict) -> types.ModuleType:
    """A stub rule: fires on every link whose mass exceeds its `limit` option."""
    rule = types.ModuleType(f"inertia_kit.lint.rules.{code.lower()}_{name.replace('-', '_')}")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = code, name, Severity.WARNING, "link"
    rule.SUMMARY, rule.OPTIONS, rule.DEFAULTS = name, options, defaults

    def check(link, ctx):
        mass = None if link.link.inertial is None else link.link.inertial.mass
        if isinstance(mass, float) and mass > ctx.option("limit"):
            yield ctx.finding(f"{link.name}: {mass} > {ctx.option('limit')}", link.link.source)

    rule.check = check
    return rule


HEAVY = _rule(
    "IN098",
    "stub-heavy",
    {"limit": float, "count": int, "strict": bool, "links": list[str], "mode": str},
    {"limit": 1.0, "count": 3, "strict": False, "links": [], "mode": "a"},
)
OTHER = _rule("IN099", "stub-other", {"limit": float}, {"limit": 100.0})


@pytest.fixture(autouse=True)
def stubs(monkeypatch):
    monkeypatch.setattr(registry, "load_rules", lambda *names: (HEAVY, OTHER))


FULL = """
[project]
name = "x"

[tool.inertia-kit]
select = ["IN0", "in09"]
extend-select = ["stub-other"]
ignore = ["IN012"]
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
        ignore=("IN012",),
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


def test_inertia_kit_toml_has_the_keys_at_the_top(tmp_path):
    path = write(tmp_path / ".inertia-kit.toml", 'select = ["IN098"]\n[rules.IN098]\nlimit = 5.5\n')
    config = load_config(path)
    assert config.select == ("IN098",)
    assert config.options == {"IN098": {"limit": 5.5}}


def test_discovery_nearest_wins_and_pyproject_without_section_is_passed_over(tmp_path):
    top = write(tmp_path / "pyproject.toml", '[tool.inertia-kit]\nselect = ["IN098"]\n')
    middle = tmp_path / "a"
    write(middle / "pyproject.toml", '[project]\nname = "inertia-kit-user"\n')  # no section
    inner = tmp_path / "a" / "b"
    own = write(inner / ".inertia-kit.toml", 'select = ["IN099"]\n')
    write(inner / "pyproject.toml", '[tool.inertia-kit]\nselect = ["IN098"]\n')
    assert find_config(inner) == own  # .inertia-kit.toml before pyproject.toml
    assert find_config(inner / "c") == own  # a folder that does not exist yet: its parents
    assert find_config(middle) == top
    # a broken pyproject.toml that does not mention us is never parsed
    write(middle / "pyproject.toml", "this is [not toml")
    assert find_config(middle) == top


def test_finder_reads_each_file_once_and_explicit_config_wins(tmp_path, monkeypatch):
    write(tmp_path / "pyproject.toml", '[tool.inertia-kit]\nselect = ["IN098"]\n')
    reads = []
    real = config_module.load_config
    monkeypatch.setattr(config_module, "load_config", lambda p: reads.append(p) or real(p))
    finder = ConfigFinder()
    for name in ("a.urdf", "b.urdf", "sub/c.urdf", "sub/d.urdf"):
        assert finder.for_file(tmp_path / name).select == ("IN098",)
    assert reads == [tmp_path / "pyproject.toml"]
    other = write(tmp_path / "elsewhere.toml", 'select = ["IN099"]\n')
    assert ConfigFinder(other).for_file(tmp_path / "a.urdf").select == ("IN099",)


def test_no_config_gives_the_defaults(tmp_path):
    assert ConfigFinder().for_file(tmp_path / "robot.urdf") == Config()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (
            "[tool.inertia-kit]\nselct = []\n",
            "`tool.inertia-kit.selct`: unknown key (did you mean `select`?); known here: "
            "`select`, `extend-select`, `ignore`, `per-file-ignores`, `fail-on`, `engines`, "
            "`rules`, `links`",
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
            "`tool.inertia-kit.ignore`: `IN9` is no rule code, code prefix or rule name",
        ),
        (
            '[tool.inertia-kit]\nselect = ["stub-hevy"]\n',
            "`tool.inertia-kit.select`: `stub-hevy` is no rule code, code prefix or rule name "
            "(did you mean `stub-heavy`?)",
        ),
        (
            '[tool.inertia-kit.per-file-ignores]\n"*.urdf" = ["IN777"]\n',
            '`tool.inertia-kit.per-file-ignores."*.urdf"`: `IN777` is no rule code, code prefix '
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
            "[tool.inertia-kit.rules.IN012]\nseverity = 'error'\n",
            "`tool.inertia-kit.rules.IN012`: rule IN012 (inertia-too-small) is not available in "
            "this version",
        ),
        (
            "[tool.inertia-kit.rules.IN999]\nseverity = 'error'\n",
            "`tool.inertia-kit.rules.IN999`: unknown rule: `IN999` is no rule code, code prefix "
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
            "`tool.inertia-kit.links.arm.mass`: expected a positive number, got -2",
        ),
        (
            "[tool.inertia-kit.links.arm]\ndensity = inf\n",
            "`tool.inertia-kit.links.arm.density`: expected a positive number, got inf",
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


def test_bad_toml_and_missing_or_misplaced_tables(tmp_path):
    broken = write(tmp_path / "pyproject.toml", "[tool.inertia-kit\nselect = 1\n")
    with pytest.raises(ConfigError, match=r"pyproject.toml: invalid TOML: .*line 1"):
        load_config(broken)
    # found by discovery too: it mentions inertia-kit, so it must be read
    with pytest.raises(ConfigError, match="invalid TOML"):
        find_config(tmp_path)
    plain = write(tmp_path / "other" / "pyproject.toml", '[project]\nname = "x"\n')
    with pytest.raises(ConfigError, match=r"pyproject.toml: no \[tool.inertia-kit\] table"):
        load_config(plain)
    nested = write(tmp_path / ".inertia-kit.toml", '[tool.inertia-kit]\nselect = ["IN098"]\n')
    with pytest.raises(ConfigError) as caught:
        load_config(nested)
    assert "`tool`: unknown key" in str(caught.value)
    with pytest.raises(ConfigError, match="no such configuration file"):
        load_config(tmp_path / "missing.toml")
    with pytest.raises(ConfigError, match="is a directory"):
        load_config(tmp_path / "other")
    latin = tmp_path / "latin.toml"
    latin.write_bytes(b'select = ["\xe9"]\n')
    with pytest.raises(ConfigError, match="not UTF-8"):
        load_config(latin)


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


def test_selection_from_config_and_command_line():
    config = Config(
        select=("IN09",),
        extend_select=("IN012",),
        ignore=("IN099",),
        options={"IN098": {"limit": 3.0}},
        severities={"IN098": Severity.ERROR},
    )
    selection = selection_for(config)
    assert (selection.select, selection.ignore) == (("IN09", "IN012"), ("IN099",))
    assert selection.options == {"IN098": {"limit": 3.0}}
    assert selection.severities == {"IN098": Severity.ERROR}
    assert selection.enabled([HEAVY, OTHER]) == [HEAVY]
    # --ignore adds to the configured ignores
    assert selection_for(config, ignore=("IN098",)).enabled([HEAVY, OTHER]) == []
    # --select replaces the configured select *and* ignore (ruff's rule)
    chosen = selection_for(config, select=("IN099",))
    assert (chosen.select, chosen.ignore) == (("IN099",), ())
    assert chosen.enabled([HEAVY, OTHER]) == [OTHER]
    assert chosen.options == config.options  # options and severities still apply
    assert selection_for(Config()).select == Selection().select == ("IN0",)


def test_config_options_severities_and_ignores_reach_the_rules(tmp_path):
    write(tmp_path / "robots" / "arm.urdf", ROBOT)
    write(tmp_path / "robots" / "legacy" / "old.urdf", ROBOT)

    def lint(text: str, **kw):
        write(tmp_path / "pyproject.toml", text)
        return {
            Path(r.path).name: [(f.code, str(f.severity)) for f in r.findings]
            for r in lint_paths([tmp_path / "robots"], **kw)
        }

    both = {"arm.urdf": [("IN098", "warning")], "old.urdf": [("IN098", "warning")]}
    assert lint("[tool.inertia-kit]\n") == both  # default limit 1 kg < 3 kg
    assert lint("[tool.inertia-kit.rules.IN098]\nlimit = 5\n") == {
        "arm.urdf": [],
        "old.urdf": [],
    }
    assert lint('[tool.inertia-kit.rules.stub-heavy]\nseverity = "info"\n') == {
        "arm.urdf": [("IN098", "info")],
        "old.urdf": [("IN098", "info")],
    }
    assert lint('[tool.inertia-kit.per-file-ignores]\n"robots/legacy/*" = ["IN09"]\n') == {
        "arm.urdf": [("IN098", "warning")],
        "old.urdf": [],
    }
    assert lint('[tool.inertia-kit]\nignore = ["IN098"]\n') == {"arm.urdf": [], "old.urdf": []}
    assert lint('[tool.inertia-kit]\nignore = ["IN098"]\n', select=("IN098",)) == both


def test_fail_on_from_config_and_command_line(tmp_path):
    write(tmp_path / "arm.urdf", ROBOT)
    write(tmp_path / "pyproject.toml", '[tool.inertia-kit]\nfail-on = "error"\n')
    (result,) = lint_paths([tmp_path / "arm.urdf"])
    assert result.fail_on is Severity.ERROR and result.findings and not result.failing
    (result,) = lint_paths([tmp_path / "arm.urdf"], fail_on=Severity.INFO)
    assert result.fail_on is Severity.INFO and result.failing == result.findings


def test_command_line_selectors_are_checked(tmp_path):
    with pytest.raises(ConfigError, match=r"--select: `IN98` is no rule code.*`IN098`"):
        lint_paths([tmp_path], select=("IN98",))
    with pytest.raises(ConfigError, match=r"--ignore: `stub-heavyy` is no rule code.*stub-heavy"):
        lint_paths([tmp_path], ignore=("stub-heavyy",))


# --- the engine: what the selection does to what rules yield ----------------------------------


def test_run_rules_keeps_two_messages_at_one_place_and_drops_repeats(tmp_path):
    from inertia_kit.analysis.links import analyse
    from inertia_kit.description.loader import load
    from inertia_kit.lint.runner import run_rules

    rule = types.ModuleType("inertia_kit.lint.rules.in097_stub_twice")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = "IN097", "stub-twice", Severity.ERROR, "robot"
    rule.SUMMARY, rule.OPTIONS, rule.DEFAULTS = "", {}, {}

    def check(robot, ctx):
        for message in ("first", "second", "first"):
            # escalating to error, which a configured severity overrides
            yield ctx.finding(message, robot.robot.source, severity=Severity.ERROR)
        yield ctx.finding("nowhere", None)

    rule.check = check
    analysis = analyse(load(write(tmp_path / "r.urdf", ROBOT)))
    findings = run_rules(analysis, Selection(), rules=[rule])
    assert [(f.path, f.message) for f in findings] == [
        ("", "nowhere"),
        (str(tmp_path / "r.urdf"), "first"),
        (str(tmp_path / "r.urdf"), "second"),
    ]
    quiet = run_rules(analysis, Selection(severities={"IN097": Severity.INFO}), rules=[rule])
    assert {f.severity for f in quiet} == {Severity.INFO}
    assert run_rules(analysis, Selection(ignore=("stub-twice",)), rules=[rule]) == []


def test_lint_file_places_findings_without_a_source_in_the_linted_file(tmp_path, monkeypatch):
    rule = types.ModuleType("inertia_kit.lint.rules.in097_stub_nowhere")
    rule.CODE, rule.NAME, rule.SEVERITY, rule.SCOPE = (
        "IN097",
        "stub-nowhere",
        Severity.ERROR,
        "robot",
    )
    rule.SUMMARY, rule.OPTIONS, rule.DEFAULTS = "", {}, {}
    rule.check = lambda robot, ctx: iter([ctx.finding("somewhere in the robot", None)])
    monkeypatch.setattr(registry, "load_rules", lambda *names: (rule,))
    path = write(tmp_path / "r.urdf", ROBOT)
    from inertia_kit.lint.runner import lint_file

    (finding,) = lint_file(path).findings
    assert (finding.path, finding.line) == (str(path), None)
