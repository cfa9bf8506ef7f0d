"""
Reports written in pieces (issue 23, item 5): every format gives, piece by piece from findings
kept on disk, the very text it renders from a list, and the JSON documents are the text
``json.dumps`` writes whatever their entries.
"""

from __future__ import annotations

import json
import tempfile

import pytest
from hypothesis import given
from hypothesis import strategies as st

from inertia_kit.description.edits import Edit
from inertia_kit.errors import InputError, InternalError
from inertia_kit.lint.findings import Finding, Fix, Safety, Severity
from inertia_kit.lint.output import FORMATS, pieces, render
from inertia_kit.lint.output.common import ENTRIES, dumps, dumps_streamed
from inertia_kit.lint.output.spool import Spool

CODES = [("IN097", "stub-non-positive"), ("IN098", "stub-heavy"), ("IN099", "stub-light")]


def findings(count: int) -> list[Finding]:
    """``count`` findings over a few files, with what each format writes of a finding: fixes,
    macro places, robots they came through, details over several lines, odd characters."""
    made = []
    for n in range(count):
        code, name = CODES[n % 3]
        fix = None
        if n % 4 == 0:
            edit = Edit(f"robots/r{n % 7}.urdf", 10 * n, 10 * n + 3, "0.1")
            fix = Fix("set the mass", (edit,), Safety.SAFE if n % 8 == 0 else Safety.UNSAFE)
        made.append(
            Finding(
                f"robots/r{n % 7}.urdf",
                n + 1 if n % 5 else None,
                3 if n % 2 else None,
                code,
                name,
                Severity(n % 3),
                f"link `l{n}` \u202e weighs {n}\x1b kg",
                link=f"l{n}",
                expected={"mass": n * 0.5, "ixx": float("nan")} if n % 3 == 0 else None,
                detail=f"the basis\nthe arithmetic {n}" if n % 2 else None,
                help="do this" if n % 3 else None,
                fix=fix,
                macro_path="macros.xacro" if n % 6 == 0 else None,
                macro_line=4 if n % 6 == 0 else None,
                via=("a.urdf.xacro", "b.urdf.xacro") if n % 9 == 0 else (),
            )
        )
    return made


ERRORS = [
    InputError("not XML: mismatched tag", "robots/bad.urdf", line=3, column=1),
    InternalError("KeyError: 'x'", "robots/odd.urdf"),
]


@pytest.mark.parametrize("output_format", FORMATS)
@pytest.mark.parametrize("count", [0, 1, 700])
def test_each_format_in_pieces_from_disk_is_its_rendered_text(output_format, count):
    listed = findings(count)
    linted = ["robots/clean.urdf", *{f.path for f in listed}]
    options = {"errors": ERRORS, "unsafe_fixes": True, "linted": linted}
    with Spool() as spool:
        spool.extend(listed)
        written = list(pieces(spool, output_format, **options))
    assert "".join(written) == render(listed, output_format, **options)
    if count == 700 and output_format != "junit":
        # written as they come, not as one text at the end (junit: a piece a file)
        assert len(written) > 2


def test_a_spool_is_a_sequence_that_reads_through_its_reader():
    listed = findings(5)
    with Spool(lambda f: f.__class__(**{**f.__dict__, "message": "redacted"})) as spool:
        spool.extend(listed[:2])
        spool.extend(listed[2:])
        assert len(spool) == 5
        assert [f.line for f in spool] == [f.line for f in listed]
        assert spool[3].line == listed[3].line
        assert [f.line for f in spool[1:4]] == [f.line for f in listed[1:4]]
        assert {f.message for f in spool} == {"redacted"}
        # read twice (sarif lists the rules before the results)
        assert list(spool) == list(spool)


def test_without_a_temporary_folder_a_spool_keeps_its_findings_in_memory(monkeypatch):
    def no_temporary_file(*args, **kwargs):
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(tempfile, "TemporaryFile", no_temporary_file)
    listed = findings(4)
    with Spool() as spool:
        spool.extend(listed)
        assert list(spool) == listed
        assert spool[2] == listed[2]
        assert "".join(pieces(spool, "json")) == render(listed, "json")


_VALUES = st.recursive(
    st.none()
    | st.booleans()
    | st.integers()
    | st.floats(allow_nan=False, allow_infinity=False)
    | st.text(),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(), inner, max_size=3),
    max_leaves=12,
)


@given(entries=st.lists(_VALUES, max_size=5), around=st.dictionaries(st.text(), _VALUES))
def test_a_document_dumped_in_pieces_is_the_document_dumped_whole(entries, around):
    for document, whole in (
        ([ENTRIES], entries),
        ({**around, "runs": [{"results": [ENTRIES]}]}, {**around, "runs": [{"results": entries}]}),
    ):
        text = "".join(dumps_streamed(document, iter(entries)))
        assert text == dumps(whole) + "\n"
        assert json.loads(text) == json.loads(dumps(whole))


def test_a_spool_whose_disk_fills_up_keeps_the_rest_in_memory(monkeypatch):
    import pickle as pickling

    listed = findings(10)
    real_dump = pickling.dump
    written = []

    def dump_until_full(value, file, *args):
        if len(written) == 3:  # the 4th of the second batch
            file.write(b"\x80partial")  # a record cut short by the full disk
            raise OSError(28, "No space left on device")
        written.append(value)
        return real_dump(value, file, *args)

    with Spool() as spool:
        spool.extend(listed[:4])
        monkeypatch.setattr(pickling, "dump", dump_until_full)
        spool.extend(listed[4:])
        assert list(spool) == listed
        assert spool[7] == listed[7] and len(spool) == 10
        assert len(written) == 3  # the rest went to memory, not to the full disk
        spool.extend(listed[:1])  # in memory from now on
        assert len(spool) == 11 and len(written) == 3
        assert "".join(pieces(spool, "json")) == render([*listed, listed[0]], "json")
