"""Configuration files: discovery, reading once, top-level keys, unreadable or misplaced files."""

from __future__ import annotations

import pytest
from stub_rules import write

from inertia_kit.errors import ConfigError
from inertia_kit.lint import config_files
from inertia_kit.lint.config import Config
from inertia_kit.lint.config_files import ConfigFinder, find_config, load_config

pytestmark = pytest.mark.usefixtures("stub_rules")


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
    real = config_files.load_config
    monkeypatch.setattr(config_files, "load_config", lambda p: reads.append(p) or real(p))
    finder = ConfigFinder()
    for name in ("a.urdf", "b.urdf", "sub/c.urdf", "sub/d.urdf"):
        assert finder.for_file(tmp_path / name).select == ("IN098",)
    assert reads == [tmp_path / "pyproject.toml"]
    other = write(tmp_path / "elsewhere.toml", 'select = ["IN099"]\n')
    assert ConfigFinder(other).for_file(tmp_path / "a.urdf").select == ("IN099",)


def test_no_config_gives_the_defaults(tmp_path):
    assert ConfigFinder().for_file(tmp_path / "robot.urdf") == Config()


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


def test_a_folder_that_may_not_be_searched_holds_no_configuration(tmp_path):
    """The nearest readable one applies (Path.is_file raised there: fuzz input 72)."""
    from kit.permissions import obeying_permissions

    write(tmp_path / ".inertia-kit.toml", "ignore = ['IN025']\n")
    hidden = tmp_path / "hidden"
    write(hidden / ".inertia-kit.toml", "ignore = ['IN020']\n")
    hidden.chmod(0)
    try:
        found = obeying_permissions(lambda: find_config(hidden))
    finally:
        hidden.chmod(0o755)
    assert found == tmp_path / ".inertia-kit.toml"
