"""
README.md and docs/ hold what a newcomer reads, and cannot drift from what the code does:

- every ```console run of `inertia-lint`, `inertia-fill` or `inertia-kit` they show prints what
  the command prints today (a line `...` stands for what a run shortened);
- README's set-up section holds exactly two fenced commands, the second being what `.ci/run`
  runs, with the suite's duration and the quick variant beside it;
- every relative link resolves, to a file and, with `#anchor`, to a heading in it; every page of
  docs/ is linked from README;
- every `[tool.inertia-kit]` TOML block is a configuration inertia-kit accepts;
- the pre-commit recipes name the hooks of `.pre-commit-hooks.yaml`, a `repo: local` hook as
  the manifest declares it, and the docs/pre-commit.md recipe runs for real (slow).
"""

from __future__ import annotations

import os
import re
import shlex
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
import yaml
from click.testing import CliRunner
from kit import EXAMPLES, REPO

from inertia_kit.cli import main as kit_command
from inertia_kit.cli.fill import fill_command
from inertia_kit.cli.lint import lint_command
from inertia_kit.lint.config import parse_config

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = REPO
README = ROOT / "README.md"
DOCS = [README, *sorted((ROOT / "docs").glob("*.md"))]
TEXTS = {path: path.read_text(encoding="utf-8") for path in DOCS}
COMMANDS = {"inertia-lint": lint_command, "inertia-fill": fill_command, "inertia-kit": kit_command}
RUN = re.compile(
    r"```console\n\$ ((?:inertia-lint|inertia-fill|inertia-kit) [^\n]*)\n(.*?)```", re.S
)
FENCE = re.compile(r"^[ \t]*```(\w*)\n(.*?)^[ \t]*```", re.M | re.S)
RUNS = [
    (path, command, shown) for path, text in TEXTS.items() for command, shown in RUN.findall(text)
]
MANIFEST = yaml.safe_load((ROOT / ".pre-commit-hooks.yaml").read_text())


def _without_inertials(where: Path) -> None:
    """docs/fill.md's first run: a copy of the pan-tilt example with its inertials removed."""
    shutil.copytree(EXAMPLES / "pan_tilt_description", where / "pan_tilt_description")
    urdf = where / "pan_tilt_description" / "urdf" / "pan_tilt.urdf"
    text = urdf.read_text()
    stripped = re.sub(r"\n[ \t]*<inertial>.*?</inertial>", "", text, flags=re.S)
    assert stripped != text
    urdf.write_text(stripped)


#: runs shown on something other than the repository as it is
PREPARED = {
    "inertia-fill --material aluminium --mass base=0.9 --diff "
    "pan_tilt_description/urdf/pan_tilt.urdf": _without_inertials,
}


def _folder(command: str, tmp_path: Path) -> Path:
    """Where the run is made: a prepared copy, the repository's top, or examples/."""
    if command in PREPARED:
        PREPARED[command](tmp_path)
        return tmp_path
    paths = [a for a in shlex.split(command)[1:] if "/" in a and not a.startswith("-")]
    for folder in (ROOT, EXAMPLES):
        if all((folder / p).exists() for p in paths):
            return folder
    raise AssertionError(f"no folder holds the paths of `{command}`")


def test_the_docs_have_runs():
    assert len([r for r in RUNS if r[0] == README]) >= 3
    assert {command.split()[0] for _, command, _ in RUNS} == set(COMMANDS)


@pytest.mark.parametrize("path, command, shown", RUNS, ids=[f"{p.name}: {c}" for p, c, _ in RUNS])
def test_run_shown_is_what_the_command_prints(path, command, shown, tmp_path, monkeypatch):
    monkeypatch.chdir(_folder(command, tmp_path))
    words = shlex.split(command)
    result = CliRunner().invoke(COMMANDS[words[0]], words[1:])
    assert result.exit_code in (0, 1), result.output
    printed = result.stdout + result.stderr
    if "...\n" not in shown:
        assert shown in (result.stdout, printed)
        return
    at = 0
    for part in shown.split("...\n"):
        found = printed.find(part, at)
        assert found >= 0, f"{path.name}: not printed by `{command}`:\n{part}"
        at = found + len(part)


# --- README's set-up section ----------------------------------------------------------------


def _section(text: str, title: str) -> str:
    (section,) = [s for s in re.split(r"^## ", text, flags=re.M) if s.startswith(title + "\n")]
    return section


SET_UP = _section(TEXTS[README], "Set up")


def test_set_up_has_exactly_two_commands():
    fences = FENCE.findall(SET_UP)
    assert [language for language, _ in fences] == ["sh", "sh"]
    first, second = (body.strip() for _, body in fences)
    assert "\n" not in first and "\n" not in second  # one command each, to copy and run
    assert first.startswith("pip install . && inertia-lint examples/")
    assert second.startswith("pip install -e '.[test]' && ")
    assert "pytest" in second


def test_set_up_says_how_long_the_suite_takes_and_what_it_downloads():
    assert re.search(
        r"about [\d.]+ minutes on the 2-core \S+ VM; measured \d+ s, \d+ tests", SET_UP
    )
    assert '-m "not slow"' in SET_UP
    assert re.search(r"\d+ MB", SET_UP)
    assert "pip download" in SET_UP


def _commands(text: str) -> list[list[str]]:
    """The shell commands of a script, split at `&&` and lines, comments left out."""
    found = []
    for line in text.replace("\\\n", " ").splitlines():
        if line.lstrip().startswith("#"):
            continue
        for part in line.split("&&"):
            try:
                found.append(shlex.split(part, comments=True))
            except ValueError:  # a shell construct across the `&&`: no command of ours
                continue
    return found


def _runs(line: list[str], want: list[str]) -> bool:
    """`want` in `line`, in order, other words (`python3 -m`, pip's flags) between them."""
    words = iter(line)
    return all(any(w == x or w.endswith("/" + x) for w in words) for x in want)


def test_ci_runs_the_second_set_up_command():
    """.ci/run runs each step of README's second command, in the same order."""
    second = FENCE.findall(SET_UP)[1][1].strip()
    script = _commands((ROOT / ".ci" / "run").read_text())
    at = 0
    for step in second.split("&&"):
        want = shlex.split(step)
        matched = [i for i in range(at, len(script)) if _runs(script[i], want)]
        assert matched, f".ci/run does not run `{step.strip()}` (after the steps before it)"
        at = matched[0] + 1


# --- links --------------------------------------------------------------------------------


def _headings(text: str) -> set[str]:
    """GitHub's anchors for the headings of a Markdown text (fenced code left out)."""
    anchors, fenced = set(), False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
        elif not fenced and (m := re.match(r"#{1,6} (.+)", line)):
            anchors.add(re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-"))
    return anchors


def _links(text: str) -> list[str]:
    prose = FENCE.sub("", text)
    return [t for t in re.findall(r"\]\(([^)\s]+)\)", prose) if not re.match(r"[a-z]+:", t)]


LINKS = [(path, target) for path, text in TEXTS.items() for target in _links(text)]


@pytest.mark.parametrize("path, target", LINKS, ids=[f"{p.name}: {t}" for p, t in LINKS])
def test_link_resolves(path: Path, target: str):
    file, _, anchor = target.partition("#")
    linked = (path.parent / file).resolve() if file else path
    assert linked.exists(), f"{path.name}: {target}: no such file"
    if anchor and linked.suffix == ".md":
        assert anchor in _headings(linked.read_text(encoding="utf-8")), (
            f"{path.name}: {target}: no such heading"
        )


def test_every_page_of_docs_is_linked_from_the_readme():
    linked = {(ROOT / t.partition("#")[0]).resolve() for t in _links(TEXTS[README])}
    for page in DOCS[1:]:
        assert page.resolve() in linked, f"README does not link {page.relative_to(ROOT)}"


# --- configuration and pre-commit recipes ----------------------------------------------------

TOML = [
    (path, body)
    for path, text in TEXTS.items()
    for language, body in FENCE.findall(text)
    if language == "toml" and "[tool.inertia-kit" in body
]


@pytest.mark.parametrize("path, body", TOML, ids=[f"{p.name}-{i}" for i, (p, _) in enumerate(TOML)])
def test_configuration_shown_is_accepted(path: Path, body: str, tmp_path):
    parse_config(tomllib.loads(body)["tool"]["inertia-kit"], tmp_path / "pyproject.toml")


def _pre_commit_configs() -> list[tuple[Path, dict]]:
    found = []
    for path, text in TEXTS.items():
        for language, body in FENCE.findall(text):
            if language == "yaml" and "hooks:" in body and "repos:" in body:
                found.append((path, yaml.safe_load(body)))
    return found


def test_pre_commit_recipes_name_the_hooks_this_repository_declares():
    configs = _pre_commit_configs()
    assert {path.name for path, _ in configs} >= {"README.md", "pre-commit.md"}
    declared = {hook["id"]: hook for hook in MANIFEST}
    for path, config in configs:
        for repo in config["repos"]:
            for hook in repo["hooks"]:
                assert hook["id"] in declared, f"{path.name}: no hook {hook['id']}"
                # no release tag exists: a recipe pins a commit (`pre-commit autoupdate` writes it)
                assert repo["repo"] == "local" or re.fullmatch(
                    r"HEAD|[0-9a-f]{40}", str(repo["rev"])
                ), f"{path.name}: {repo['rev']}: no such tag; pin a commit"

                if repo["repo"] != "local":
                    continue
                # a local hook runs the installed command as the manifest's hook runs it
                assert hook["language"] == "system"
                for key in ("name", "entry", "require_serial", "types", "files"):
                    assert hook[key] == declared[hook["id"]][key], (path.name, hook["id"], key)


@pytest.mark.slow
def test_the_local_recipe_runs(tmp_path):
    """docs/pre-commit.md's `repo: local` recipe on a copy of examples/: the hooks fail on the
    seed robots' findings; after `inertia-lint --add-noqa .` both pass."""
    pytest.importorskip("pre_commit")
    (config,) = [
        c
        for p, c in _pre_commit_configs()
        if p.name == "pre-commit.md" and c["repos"][0]["repo"] == "local"
    ]
    project = tmp_path / "robots"
    shutil.copytree(EXAMPLES, project)
    (project / ".pre-commit-config.yaml").write_text(yaml.safe_dump(config))
    scripts = sysconfig.get_path("scripts")
    env = {
        **os.environ,
        "PATH": os.pathsep.join([scripts, str(Path(sys.executable).parent), os.environ["PATH"]]),
        "PRE_COMMIT_HOME": str(tmp_path / "cache"),
        "NO_COLOR": "1",
    }
    env.pop("PRE_COMMIT", None)

    def run(*args: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            args, cwd=project, env=env, capture_output=True, text=True, timeout=600
        )

    git = ("git", "-c", "user.name=t", "-c", "user.email=t@example.org")
    run(*git, "init", "-q")
    run(*git, "add", "-A")
    run(*git, "commit", "-q", "-m", "robots")
    hooks = (sys.executable, "-m", "pre_commit", "run", "--all-files", "--color", "never")
    first = run(*hooks)
    assert first.returncode == 1, first.stdout + first.stderr
    assert re.search(r"inertia-lint\.+Failed", first.stdout), first.stdout
    assert re.search(r"inertia-fill\.+Failed", first.stdout), first.stdout
    assert "files were modified by this hook" in first.stdout

    run(*git, "checkout", "-q", "--", ".")
    adopt = run(os.path.join(scripts, "inertia-lint"), "--add-noqa", ".")
    assert adopt.returncode == 0, adopt.stdout + adopt.stderr
    run(*git, "add", "-A")
    second = run(*hooks)
    assert second.returncode == 0, second.stdout + second.stderr
    assert re.search(r"inertia-lint\.+Passed", second.stdout)
    assert re.search(r"inertia-fill\.+Passed", second.stdout)
