"""The `full` format, the default: location, source line, caret, macro body line, help."""

from __future__ import annotations

import pytest
from output_kit import NO_FINDINGS, NOTE, SUMMARY, lint, no_findings

from inertia_kit.lint.findings import Finding, Severity
from inertia_kit.lint.output import render

FULL = """\
robots/arm.urdf:10:7: IN097 [error] link `upper`: mass = 0 kg is not positive
   |
10 |       <mass value="0"/>
   |       ^^^^^
   = help: give the link's real mass

robots/arm.urdf:20:7: IN098 [warning] link `fore`: 25 kg, more than 10 kg
   |
20 |       <mass value="25"/>
   |       ^^^^^
   = detail: a stub's limit: 10 kg

robots/cart.urdf.xacro:6:7: IN099 [info] 0.005 kg
  |
6 |       <mass value="0.005"/>
  |       ^^^^^

robots/cart.urdf.xacro:10:3: IN097 [error] link `left_wheel`: mass = -1 kg is not positive
   |
10 |   <xacro:wheel name="left" mass="-1"/>
   |   ^^^^^^^^^^^^
   = in the macro body: robots/wheel.xacro:10
   |
10 |         <mass value="${mass}"/>
   |         ^^^^^
   = help: give the link's real mass

"""


def test_full_exactly(robots):
    assert lint("--output-format", "full", "robots") == (1, FULL, NOTE + SUMMARY)


def test_full_is_the_default(robots):
    assert lint("robots") == (1, FULL, NOTE + SUMMARY)


def test_full_without_findings(robots):
    assert no_findings("full") == (0, "", NO_FINDINGS)


def test_full_without_a_source_line_and_with_tabs(tmp_path):
    tabbed = tmp_path / "t.urdf"
    tabbed.write_text("<robot>\n\t<link name='a'/>\n</robot>\n")
    findings = [
        Finding(str(tabbed), 2, 2, "IN097", "n", Severity.WARNING, "tabbed"),
        Finding(str(tmp_path / "gone.urdf"), 4, 1, "IN097", "n", Severity.ERROR, "no file"),
        Finding(str(tabbed), None, None, "IN097", "n", Severity.ERROR, "whole robot"),
    ]
    assert render(findings, "full") == (
        f"{tabbed}:2:2: IN097 [warning] tabbed\n"
        "  |\n"
        "2 |     <link name='a'/>\n"
        "  |     ^^^^^\n"
        "\n"
        f"{tmp_path / 'gone.urdf'}:4:1: IN097 [error] no file\n"
        "\n"
        f"{tabbed}: IN097 [error] whole robot\n"
        "\n"
    )


def _shown(tmp_path, line: str, column: int | None, name: str = "long.urdf") -> list[str]:
    """The source line and caret lines `full` prints for a finding at ``column`` of ``line``."""
    path = tmp_path / name
    path.write_text(line + "\n", encoding="utf-8")
    finding = Finding(str(path), 1, column, "IN097", "n", Severity.ERROR, "m")
    return render([finding], "full").splitlines()[2:4]


def test_a_long_line_is_shown_as_an_excerpt_around_the_element(tmp_path):
    # a minified one-line robot: each finding shows a bounded excerpt, not the whole line
    links = "".join(f'<link name="l{i}"><mass value="-1"/></link>' for i in range(2000))
    line = f"<robot>{links}</robot>"
    column = line.index('<link name="l1000">') + 1
    source, caret = _shown(tmp_path, line, column)
    shown = source.removeprefix("1 | ")
    assert shown.startswith("…") and shown.endswith("…")
    assert len(shown) == 122  # EXCERPT characters and the two cuts
    assert shown[caret.index("^") - 4 :].startswith('<link name="l1000">')
    assert caret.removeprefix("  |").strip() == "^" * len("<link")
    # the whole output grows with the findings, not with findings × line length
    findings = [
        Finding(str(tmp_path / "long.urdf"), 1, c + 1, "IN097", "n", Severity.ERROR, "m")
        for c in range(0, len(line), 40)
    ]
    assert len(render(findings, "full")) < 300 * len(findings)


def test_an_excerpt_at_either_end_of_a_long_line(tmp_path):
    line = "<robot>" + "x" * 500 + "<link/>"
    source, caret = _shown(tmp_path, line, 1)
    assert source == "1 | <robot>" + "x" * 113 + "…" and caret == "  | ^^^^^^"
    source, caret = _shown(tmp_path, line, len(line) - 6)
    assert source == "1 | …" + "x" * 113 + "<link/>"
    assert caret == "  | " + " " * 114 + "^^^^^"


@pytest.mark.parametrize(
    ("line", "shown", "offset"),
    [
        # tabs expand to stops of 4; the caret follows
        ("\t<a/>\t<link/>", "    <a/>    <link/>", 12),
        # wide characters take two columns, combining marks none
        ('<a n="腕腕"/><link/>', '<a n="腕腕"/><link/>', 13),
        ('<a n="e\u0301"/><link/>', '<a n="e\u0301"/><link/>', 10),
        # what would break or disguise the line is escaped, and the caret counts its escape
        ('<a n="\u2028\u202e"/><link/>', '<a n="\\u2028\\u202e"/><link/>', 21),
    ],
)
def test_the_caret_stays_under_the_element(tmp_path, line, shown, offset):
    source, caret = _shown(tmp_path, line, line.index("<link") + 1)
    assert source == f"1 | {shown}"
    assert caret == "  | " + " " * offset + "^^^^^"


def test_names_paths_and_values_are_escaped(tmp_path):
    path = tmp_path / "a\n::error::b.urdf"
    path.write_text("<robot/>\n")
    finding = Finding(
        str(path), 1, 1, "IN097", "n", Severity.ERROR, "link `x\n::error::y`",
        help="to `x\n::warning::z`", unfixable="`x\u2028`", macro_path=str(path), macro_line=1,
    )  # fmt: skip
    text = render([finding], "full")
    assert all(not line.startswith("::") for line in text.splitlines())
    assert "a\\n::error::b.urdf:1:1: IN097 [error] link `x\\n::error::y`" in text
    assert "= no fix: `x\\u2028`" in text and "= help: to `x\\n::warning::z`" in text
    assert f"in the macro body: {tmp_path}/a\\n::error::b.urdf:1" in text
