"""
The pre-commit hook: its manifest is what pre-commit accepts, its file pattern takes .urdf,
.xacro and .urdf.xacro files, and, for real, pre-commit installs this repository into a
virtualenv from a `.pre-commit-config.yaml` naming it by path and commit (as README shows; the
same config `pre-commit try-repo` writes) and its hooks fail a repository holding a bad URDF and
pass a good one; the wheel pip builds ships the rule documents.

The repository under test is a snapshot of this working tree (tracked and untracked, not
ignored files) committed to a temporary git repository: pre-commit takes committed files only,
and the tree under test may hold changes not yet committed. The hooks' virtualenv is built once
per test session (~20 s here) in a private pre-commit cache and used by every run after
(`try-repo` would build a fresh one each run). Nothing here touches this repository's git
state.
"""

from __future__ import annotations

import math
import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
import yaml
from kit import REPO
from kit.session import shared_folder
from kit.urdf import box, collision, joint_lines, link_lines, robot_lines

ROOT = REPO
MANIFEST = ROOT / ".pre-commit-hooks.yaml"

BAD = robot_lines(
    link_lines("world"), joint_lines("world", "arm"), link_lines("arm", 0, 0.001), name="bad"
)
GOOD = BAD.replace('name="bad"', 'name="good"').replace('value="0"', 'value="0.5"')
# only IN002 runs, so that rules still being written cannot change what these tests see
CONFIG = '[tool.inertia-kit]\nselect = ["IN002"]\n'


def hook(name: str = "inertia-lint") -> dict:
    (entry,) = [e for e in yaml.safe_load(MANIFEST.read_text()) if e["id"] == name]
    return entry


def test_manifest_is_valid_for_pre_commit():
    from pre_commit.clientlib import load_manifest

    loaded = load_manifest(str(MANIFEST))
    assert [h["id"] for h in loaded] == ["inertia-lint", "inertia-fill"]
    for entry in loaded:
        # as ruff's hooks: files handed over by name still honour exclude (args add to entry)
        assert entry["entry"] == f"{entry['id']} --force-exclude"
        assert entry["language"] == "python"
        assert entry["pass_filenames"] is True
        # both hooks take the same files
        assert (entry["files"], entry["types"]) == (loaded[0]["files"], loaded[0]["types"])


@pytest.mark.parametrize(
    ("name", "taken"),
    [
        ("robot.urdf", True),
        ("robot.xacro", True),
        ("robot.urdf.xacro", True),
        ("urdf/ROBOT.URDF", True),
        # every .xml: the command lints the MJCF models among them, passing over the rest
        # (tests/lint/test_discovery.py: a hook hands over every xml file ...)
        ("robot.xml", True),
        ("robot.urdf.bak", False),
        ("package.xml", True),
    ],
)
def test_hook_takes_urdf_xacro_and_xml_files(tmp_path, name, taken):
    """As pre-commit filters: the `files` regex and the identify tags (`types`)."""
    from identify import identify

    path = tmp_path / name
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(GOOD)
    entry = hook()
    tags = identify.tags_from_path(str(path))
    matched = re.search(entry["files"], name) is not None and set(entry["types"]) <= tags
    assert matched is taken


def _git(*args: str, cwd: Path) -> str:
    done = subprocess.run(
        [
            "git",
            "-c",
            "user.name=inertia-kit tests",
            "-c",
            "user.email=tests@example.invalid",
            "-c",
            "commit.gpgsign=false",
            "-c",
            "init.defaultBranch=main",
            *args,
        ],
        cwd=cwd,
        capture_output=True,
        text=True,
        check=True,
    )
    return done.stdout


def _snapshot(target: Path) -> str:
    """This working tree as a one-commit git repository at ``target``; its commit id."""
    listed = _git("ls-files", "-z", "--cached", "--others", "--exclude-standard", cwd=ROOT)
    for name in filter(None, listed.split("\0")):
        source = ROOT / name
        if not os.path.lexists(source):
            continue  # deleted in the working tree
        copy = target / name
        copy.parent.mkdir(parents=True, exist_ok=True)
        if source.is_symlink():
            os.symlink(os.readlink(source), copy)
        else:
            shutil.copy2(source, copy)
    _git("init", "-q", cwd=target)
    _git("add", "-A", cwd=target)
    _git("commit", "-q", "-m", "snapshot", cwd=target)
    return _git("rev-parse", "HEAD", cwd=target).strip()


def _project(path: Path, files: dict[str, str]) -> Path:
    path.mkdir()
    for name, text in files.items():
        (path / name).parent.mkdir(parents=True, exist_ok=True)
        (path / name).write_text(text)
    _git("init", "-q", cwd=path)
    _git("add", "-A", cwd=path)
    return path


def _hooks_configured(base: Path) -> None:
    """In ``base``: the snapshot repository and the pre-commit configuration of its hooks."""
    snapshot = base / "inertia-kit"
    snapshot.mkdir()
    commit = _snapshot(snapshot)
    hooks = [{"id": entry["id"]} for entry in yaml.safe_load(MANIFEST.read_text())]
    config = {"repos": [{"repo": str(snapshot), "rev": commit, "hooks": hooks}]}
    (base / "pre-commit-config.yaml").write_text(yaml.safe_dump(config))


@pytest.fixture(scope="module")
def hook_repo(tmp_path_factory):
    """
    (the pre-commit configuration of the snapshot repository's hooks, the snapshot, the
    environment with a pre-commit cache): one of each for the session, so the hooks'
    virtualenv is built once (pre-commit's lock on its cache makes the other workers wait).
    """
    base = shared_folder(tmp_path_factory, "precommit", _hooks_configured)
    env = {**os.environ, "PRE_COMMIT_HOME": str(base / "cache"), "NO_COLOR": "1"}
    env.pop("PRE_COMMIT", None)
    return base / "pre-commit-config.yaml", base / "inertia-kit", env


def _run_hook(
    hook_repo, project: Path, hook_id: str = "inertia-lint", files: tuple[str, ...] = ()
) -> subprocess.CompletedProcess:
    """The hook on ``files`` (as a commit of them hands them over), else on every file."""
    config, _, env = hook_repo
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "pre_commit",
            "run",
            hook_id,
            "--config",
            str(config),
            *(("--files", *files) if files else ("--all-files",)),
            "--color",
            "never",
        ],
        cwd=project,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )


@pytest.mark.slow
def test_hook_fails_a_bad_urdf(hook_repo, tmp_path):
    bad = _project(
        tmp_path / "bad",
        {"pyproject.toml": CONFIG, "urdf/bad.urdf": BAD, "urdf/good.urdf.xacro": GOOD},
    )
    done = _run_hook(hook_repo, bad)
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert re.search(r"inertia-lint\.+Failed", output), output
    assert "- exit code: 1" in output
    assert "urdf/bad.urdf:9:7: IN002 [error] link `arm`: mass = 0 kg is not positive" in output
    assert "good.urdf.xacro" not in output
    assert "Found 1 error in 1 of 2 files." in output


MJCF_BAD = """<mujoco model="arm">
  <worldbody>
    <body name="arm">
      <joint axis="0 0 1"/>
      <inertial pos="0 0 0" mass="0" diaginertia="1 1 1"/>
    </body>
  </worldbody>
</mujoco>
"""


@pytest.mark.slow
def test_hook_lints_the_mjcf_models_among_the_xml_files(hook_repo, tmp_path):
    project = _project(
        tmp_path / "mjcf",
        {
            "pyproject.toml": CONFIG,
            "package.xml": "<package format='3'><name>arm</name></package>",
            "launch/arm.launch.xml": "<launch/>",
            "mjcf/arm.xml": MJCF_BAD,
        },
    )
    done = _run_hook(hook_repo, project)
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert "mjcf/arm.xml:5:7: IN002 [error] body `arm`: mass = 0 kg is not positive" in output
    assert "package.xml" not in output and "launch" not in output
    assert "Found 1 error in 1 file." in output


@pytest.mark.slow
def test_hook_passes_a_good_urdf(hook_repo, tmp_path):
    good = _project(tmp_path / "good", {"pyproject.toml": CONFIG, "urdf/good.urdf": GOOD})
    done = _run_hook(hook_repo, good)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output
    assert re.search(r"inertia-lint\.+Passed", output), output


@pytest.mark.slow
def test_hook_leaves_out_the_files_the_configuration_excludes(hook_repo, tmp_path):
    """pre-commit hands every file over by name; `exclude` in the configuration still holds
    (`--force-exclude` in the hook's entry), and colcon's build/ beside src/ is left out."""
    config = CONFIG + 'extend-exclude = ["generated/"]\n'
    files = {"pyproject.toml": config, "src/good.urdf": GOOD}
    files.update({"generated/bad.urdf": BAD, "build/bad.urdf": BAD})
    project = _project(tmp_path / "excluded", files)
    done = _run_hook(hook_repo, project)
    output = done.stdout + done.stderr
    assert done.returncode == 0, output
    assert re.search(r"inertia-lint\.+Passed", output), output


MISSING = robot_lines(
    link_lines("world"),
    joint_lines("world", "arm"),
    f'  <link name="arm">\n    {collision(box(0.1, 0.1, 0.4))}\n  </link>\n',
    name="arm",
)


@pytest.mark.slow
def test_hook_fill_fills_then_passes(hook_repo, tmp_path):
    """The fixer writes the missing block and fails (exit 1) so the change is reviewed; run
    again on the filled file, it passes and changes nothing."""
    project = _project(tmp_path / "fill", {"urdf/arm.urdf": MISSING, "urdf/good.urdf": GOOD})
    urdf = project / "urdf" / "arm.urdf"
    done = _run_hook(hook_repo, project, "inertia-fill")
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert re.search(r"inertia-fill\.+Failed", output), output
    assert "- exit code: 1" in output
    assert "- files were modified by this hook" in output
    # 0.1 × 0.1 × 0.4 m at 1000 kg/m³: 4 kg
    assert "Filled 1 link in urdf/arm.urdf: arm 4 kg" in output
    assert "good.urdf" not in output
    filled = urdf.read_text()
    assert '    <inertial>\n      <origin xyz="0 0 0" rpy="0 0 0"/>\n' in filled
    assert '<mass value="4"/>' in filled
    assert (project / "urdf" / "good.urdf").read_text() == GOOD

    done = _run_hook(hook_repo, project, "inertia-fill")
    output = done.stdout + done.stderr
    assert done.returncode == 0, output
    assert re.search(r"inertia-fill\.+Passed", output), output
    assert urdf.read_text() == filled


@pytest.mark.slow
def test_the_wheel_ships_the_rule_documents(hook_repo, tmp_path):
    """
    A wheel built from the snapshot (what pre-commit and pip install) holds the rule
    documents as files, and `--explain` run from the unpacked wheel reads them there.
    """
    _, snapshot, env = hook_repo
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(tmp_path), "."],
        cwd=snapshot,
        env=env,
        check=True,
        capture_output=True,
        timeout=600,
    )
    (wheel,) = tmp_path.glob("inertia_kit-*.whl")
    unpacked = tmp_path / "unpacked"
    with zipfile.ZipFile(wheel) as archive:
        names = archive.namelist()
        archive.extractall(unpacked)
    documents = sorted(n for n in names if n.startswith("inertia_kit/rule_docs/"))
    shipped = sorted(p.name for p in (snapshot / "rules").glob("*.md"))
    assert [n.rsplit("/", 1)[1] for n in documents] == shipped
    explain = (
        "import sys, inertia_kit.lint.documents as r; from inertia_kit.cli import lint_main;"
        "print(r.documents_folder(), file=sys.stderr); lint_main(['--explain', 'IN002'])"
    )
    done = subprocess.run(
        [sys.executable, "-c", explain],
        cwd=tmp_path,
        env={**env, "PYTHONPATH": str(unpacked)},
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, done.stderr
    assert done.stderr.strip() == str(unpacked / "inertia_kit" / "rule_docs")
    assert done.stdout == (snapshot / "rules" / "IN002-non-positive-mass.md").read_text()


# --- a fragment edit: the robots that include it are linted (filled) --------------------------

WHEELS = "my_robot_description/urdf/wheels.xacro"
ROBOT = "my_robot_description/urdf/robot.xacro"


def _wheeled(path: Path, edit) -> Path:
    """A repository holding the seed wheeled robot, with ``edit`` applied to the text of the
    `wheel` macro (the one the robot calls) in wheels.xacro."""
    source = ROOT / "examples" / "my_robot_description"
    files = {
        f"my_robot_description/{p.relative_to(source)}": p.read_text()
        for p in source.rglob("*")
        if p.is_file()
    }
    text = files[WHEELS]
    start = text.index('<xacro:macro name="wheel"')
    end = text.index("</xacro:macro>", start)
    files[WHEELS] = text[:start] + edit(text[start:end]) + text[end:]
    return _project(path, {"pyproject.toml": CONFIG, **files})


@pytest.mark.slow
def test_hook_lint_fails_a_broken_mass_in_a_fragment(hook_repo, tmp_path):
    """`mass="-5"` in wheels.xacro, committed alone: the hook gets the fragment, lints the
    robot that includes it, and reports the finding where the edit is."""
    project = _wheeled(
        tmp_path / "wheels",
        lambda macro: macro.replace('<mass value="${wheel_mass}" />', '<mass value="-5" />'),
    )
    line = 1 + (project / WHEELS).read_text().split('<mass value="-5"')[0].count("\n")
    done = _run_hook(hook_repo, project, files=(WHEELS,))
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert re.search(r"inertia-lint\.+Failed", output), output
    for wheel in ("left", "right"):
        assert (
            f"{WHEELS}:{line}: IN002 [error] link `{wheel}_wheel_link`: mass = -5 kg is not "
            "positive"
        ) in output
    assert f"(via {ROBOT})" in output
    assert f"note: {WHEELS}: linted through the robots that include it: {ROBOT}" in output
    assert "Found 2 errors in 1 file." in output


@pytest.mark.slow
def test_hook_fill_on_a_fragment_fills_it_then_passes(hook_repo, tmp_path):
    """The wheel macro lost its <inertial>: the fill hook on wheels.xacro writes it there (and
    nowhere else), fails so the change is reviewed, and passes on the next run."""

    def drop_inertial(macro: str) -> str:
        start = macro.index("<inertial>")
        return macro[:start] + macro[macro.index("</inertial>") + len("</inertial>") :]

    project = _wheeled(tmp_path / "fill-wheels", drop_inertial)
    others = {p: p.read_bytes() for p in project.rglob("*.xacro") if p.name != "wheels.xacro"}
    done = _run_hook(hook_repo, project, "inertia-fill", files=(WHEELS,))
    output = done.stdout + done.stderr
    assert done.returncode == 1, output
    assert "- files were modified by this hook" in output
    # a solid cylinder, r = 0.05 m, l = 0.02 m (macros.xacro), at 1000 kg/m³
    mass = f"{math.pi * 0.05**2 * 0.02 * 1000:.6g}"
    assert (
        f"Filled 2 links in {WHEELS} via {ROBOT}: left_wheel_link {mass} kg, "
        f"right_wheel_link {mass} kg"
    ) in output
    filled = (project / WHEELS).read_text()
    start = filled.index('<xacro:macro name="wheel"')
    assert f'<mass value="{mass}"/>' in filled[start : filled.index("</xacro:macro>", start)]
    assert {p: p.read_bytes() for p in others} == others

    done = _run_hook(hook_repo, project, "inertia-fill", files=(WHEELS,))
    output = done.stdout + done.stderr
    assert done.returncode == 0, output
    assert re.search(r"inertia-fill\.+Passed", output), output
    assert (project / WHEELS).read_text() == filled


# --- the hooks on many files: pre-commit must not split them into batches run in parallel ----


def _examples(path: Path) -> Path:
    """A repository holding every example robot (two robots share wheels.xacro's fragment)."""
    shutil.copytree(ROOT / "examples", path)
    _git("init", "-q", cwd=path)
    _git("add", "-A", cwd=path)
    return path


def _findings(output: str) -> list[str]:
    return [line for line in output.splitlines() if re.search(r":\d+(:\d+)?: IN\d{3} \[", line)]


def test_the_hooks_run_serially():
    # pre-commit splits the files among as many parallel batches as there are cores unless a
    # hook asks not to; two batches reach a fragment through their robots (both fill it, or
    # both report its findings)
    assert all(
        entry.get("require_serial") is True for entry in yaml.safe_load(MANIFEST.read_text())
    )


@pytest.mark.slow
def test_the_hooks_give_one_result_each_run_on_the_examples(hook_repo, tmp_path):
    project = _examples(tmp_path / "examples")
    runs = [_run_hook(hook_repo, project) for _ in range(10)]
    first = runs[0].stdout + runs[0].stderr
    assert runs[0].returncode == 1, first
    found = _findings(first)
    assert found and len(found) == len(set(found)), first  # each finding once
    for done in runs[1:]:
        assert (done.returncode, _findings(done.stdout + done.stderr)) == (1, found)
    # the fill hook: the first run fills and stops the commit, every later one changes nothing
    filled = _run_hook(hook_repo, project, "inertia-fill")
    assert filled.returncode == 1, filled.stdout + filled.stderr
    assert "changed while it was being processed" not in filled.stdout + filled.stderr
    after = {p: p.read_bytes() for p in project.rglob("*") if p.is_file() and ".git" not in p.parts}
    for _ in range(9):
        done = _run_hook(hook_repo, project, "inertia-fill")
        output = done.stdout + done.stderr
        assert done.returncode == 0 and re.search(r"inertia-fill\.+Passed", output), output
        now = {
            p: p.read_bytes() for p in project.rglob("*") if p.is_file() and ".git" not in p.parts
        }
        assert now == after
