"""How `--fix` applies fixes: overlapping ones wait for the next pass, identical edits are taken
once, unsafe ones only when asked, and a file that never settles stops after MAX_PASSES."""

from __future__ import annotations

from pathlib import Path

from inertia_kit.description.edits import Edit
from inertia_kit.lint.applying import MAX_PASSES, applicable, fix_file, one_pass
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.runner import FileResult


def finding(path: Path, edits: list[tuple[int, int, str]], safety=Safety.SAFE, n=0) -> Finding:
    fix = Fix("t", tuple(Edit(str(path), s, e, c) for s, e, c in edits), safety)
    return Finding(str(path), 1, 1, "IN060", "x", Severity.WARNING, f"m{n}", fix=fix)


def test_overlapping_fixes_wait_and_identical_edits_are_taken_once(tmp_path: Path):
    path = tmp_path / "a.urdf"
    path.write_text("0123456789")
    first = finding(path, [(2, 4, "ab")], n=1)
    same = finding(path, [(2, 4, "ab")], n=2)  # a second link sharing that edit
    overlapping = finding(path, [(3, 6, "xyz")], n=3)
    apart = finding(path, [(8, 8, "!")], n=4)
    step = one_pass([first, same, overlapping, apart], unsafe=False)
    assert step.fixed == (first, same, apart)
    ((source, text),) = step.changes
    assert (source.text, text) == ("0123456789", "01ab4567!89")


def test_unsafe_fixes_only_when_asked(tmp_path: Path):
    path = tmp_path / "a.urdf"
    unsafe = finding(path, [(0, 0, "x")], Safety.UNSAFE)
    assert not applicable(unsafe, unsafe=False) and applicable(unsafe, unsafe=True)
    display = finding(path, [(0, 0, "x")], Safety.DISPLAY_ONLY)
    assert not applicable(display, unsafe=True)


def test_a_file_that_never_settles_stops_with_a_note(tmp_path: Path):
    path = tmp_path / "a.urdf"
    path.write_text("<robot/>")
    runs = []

    def lint() -> FileResult:
        runs.append(1)
        return FileResult(str(path), [finding(path, [(0, 0, "<!-- again -->")])])

    outcome = fix_file(lint, unsafe=False, write=True)
    assert (outcome.fixed, outcome.passes, outcome.settled) == (MAX_PASSES, MAX_PASSES, False)
    assert len(runs) == MAX_PASSES + 1
    assert path.read_text() == "<!-- again -->" * MAX_PASSES + "<robot/>"
    assert outcome.result.notes == [
        f"{path}: the fixes did not settle after {MAX_PASSES} passes; run inertia-lint --fix "
        "again and report the file if it still changes"
    ]


def test_diff_is_one_pass_and_writes_nothing(tmp_path: Path):
    path = tmp_path / "a.urdf"
    path.write_text("<robot/>\n")

    def lint() -> FileResult:
        return FileResult(str(path), [finding(path, [(6, 6, ' name="r"')])])

    outcome = fix_file(lint, unsafe=False, write=False)
    assert path.read_text() == "<robot/>\n"
    assert outcome.diff.splitlines()[-2:] == ["-<robot/>", '+<robot name="r"/>']


def test_a_pass_edits_only_the_text_its_lint_read(tmp_path: Path):
    """The reproducer: the edits of a lint were applied, at their old offsets, to a file saved
    since. A file whose bytes differ from those the lint read is refused, nothing written."""
    from inertia_kit.description.edits import ChangedWhileEditing
    from inertia_kit.description.reads import digest, key

    path = tmp_path / "a.urdf"
    path.write_text("<robot/>")
    read = {key(path): digest(b"<robot/>")}
    path.write_text("<!-- saved --><robot/>")

    def lint() -> FileResult:
        return FileResult(str(path), [finding(path, [(0, 0, "<!-- fix -->")])], reads=read)

    outcome = fix_file(lint, unsafe=False, write=True)
    assert isinstance(outcome.result.error, ChangedWhileEditing)
    assert path.read_text() == "<!-- saved --><robot/>"


def test_a_write_between_two_passes_is_kept_and_nothing_is_written(tmp_path: Path):
    """Another writer saved the file between two passes: the passes went on in memory, on the
    text the first lint read; the one write at the end expects that text, finds theirs and
    writes nothing (exit 2), their save kept."""
    from inertia_kit.description.edits import ChangedWhileEditing
    from inertia_kit.description.reads import digest, key
    from inertia_kit.description.safexml import read_bounded

    path = tmp_path / "a.urdf"
    path.write_text("<robot/>")
    passes = []

    def lint() -> FileResult:
        passes.append(1)
        if len(passes) == 2:
            path.write_text(path.read_text() + "<!-- theirs -->")
        data = read_bounded(path)  # as the loader reads: the previous pass's text
        fix = [finding(path, [(0, 0, "<!-- fix -->")])] if len(passes) < 3 else []
        return FileResult(str(path), fix, reads={key(path): digest(data)})

    outcome = fix_file(lint, unsafe=False, write=True)
    assert isinstance(outcome.result.error, ChangedWhileEditing)
    assert (outcome.fixed, len(passes)) == (0, 3)
    assert path.read_text() == "<robot/><!-- theirs -->"
