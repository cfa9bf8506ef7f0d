"""
Findings kept on disk until the report that holds them is written: a run over many files
streams its findings here as each file is linted, so that its memory does not grow with the
number of files, and the document formats (json, sarif, junit, gitlab) are written from here
at the end, one finding at a time.
"""

from __future__ import annotations

import pickle
from array import array
from collections.abc import Callable, Iterable, Iterator, Sequence
from typing import IO, overload

from inertia_kit.lint.findings import Finding


def _as_is(finding: Finding) -> Finding:
    return finding


class Spool(Sequence[Finding]):
    """
    A sequence of findings in a temporary file (in memory where no temporary file can be
    made), appended to with :meth:`extend`; each finding is passed through ``read`` as it is
    read back (the values ``--redact-env`` keeps out, known only once every file is linted).
    """

    def __init__(self, read: Callable[[Finding], Finding] = _as_is):
        import tempfile

        self._read = read
        self._offsets = array("q")  # where each finding starts in the file
        self._file: IO[bytes] | None = None
        self._kept: list[Finding] = []
        try:
            self._file = tempfile.TemporaryFile()  # noqa: SIM115 - closed by close()
        except OSError:  # no writable temporary folder: kept in memory
            self._file = None

    def extend(self, findings: Iterable[Finding]) -> None:
        findings = list(findings)
        written = 0
        if self._file is not None:
            try:
                self._file.seek(0, 2)
                for finding in findings:
                    at = self._file.tell()
                    pickle.dump(finding, self._file, pickle.HIGHEST_PROTOCOL)
                    self._offsets.append(at)
                    written += 1
                return
            except OSError:  # the temporary folder is full (or gone): the rest in memory
                self._to_memory()
        self._kept.extend(findings[written:])

    def _to_memory(self) -> None:
        """Every finding written so far read back into memory; the file dropped."""
        assert self._file is not None
        kept = []
        self._file.seek(0)
        for _ in range(len(self._offsets)):
            kept.append(pickle.load(self._file))
        self._file.close()
        self._file, self._kept = None, kept

    def __len__(self) -> int:
        return len(self._kept) if self._file is None else len(self._offsets)

    @overload
    def __getitem__(self, index: int) -> Finding: ...
    @overload
    def __getitem__(self, index: slice) -> list[Finding]: ...
    def __getitem__(self, index: int | slice) -> Finding | list[Finding]:
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        if self._file is None:
            return self._read(self._kept[index])
        self._file.seek(self._offsets[index])
        return self._read(pickle.load(self._file))

    def __iter__(self) -> Iterator[Finding]:
        if self._file is None:
            yield from map(self._read, list(self._kept))
            return
        count = len(self._offsets)
        for index in range(count):  # read in order; a seek each time: a reader may interleave
            yield self[index]

    def close(self) -> None:
        if self._file is not None:
            self._file.close()

    def __enter__(self) -> Spool:
        return self

    def __exit__(self, *exception: object) -> None:
        self.close()
