"""
The fuzz run (tests/fuzz): in CI a fixed seed and a few hundred inputs through every command and
format (bounded like the hypothesis run); ``INERTIA_KIT_FUZZ_INPUTS=50000`` runs that many with
the long profile (``INERTIA_KIT_FUZZ_SEED`` picks the seed, ``INERTIA_KIT_FUZZ_OUT`` where the
summary and reproducers go). Failures in the known-open classes of issue 19 (fuzz.known) are
excused, each named in a warning; any other fails the test with its reproducer command.
"""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import pytest

from fuzz.campaign import CI, LONG, run_campaign
from fuzz.known import KNOWN_OPEN, known_open
from fuzz.plan import COVERAGE

#: the CI run: inputs, and how many processes run them
CI_INPUTS = 120
CI_WORKERS = 2

pytestmark = [
    pytest.mark.skipif(not hasattr(os, "fork"), reason="the harness forks its runs"),
    pytest.mark.slow,  # about 35 s on 2 cores
]


def test_fuzz_run_finds_nothing_but_the_known_open_classes(tmp_path):
    inputs = int(os.environ.get("INERTIA_KIT_FUZZ_INPUTS") or 0)
    seed = os.environ.get("INERTIA_KIT_FUZZ_SEED") or "ci"
    profile = LONG if inputs else CI
    workers = max(1, len(os.sched_getaffinity(0))) if inputs else CI_WORKERS
    out = Path(os.environ.get("INERTIA_KIT_FUZZ_OUT") or tmp_path)
    summary = run_campaign(
        seed, list(range(inputs or CI_INPUTS)), profile, workers=workers, out=out
    )
    print(summary.text(known_open))

    for signature, entry in sorted(summary.signatures.items()):
        why = known_open(signature)
        if why:
            warnings.warn(f"fuzz: excused {entry['count']}× {signature} ({why})", stacklevel=1)
    seen = {known_open(s) for s in summary.signatures}
    for kind, pattern, why in KNOWN_OPEN:
        if why not in seen:
            print(f"known-open class not seen in this run: {kind}: {pattern} ({why})")

    unexpected = {s: e for s, e in summary.signatures.items() if not known_open(s)}
    replay = (
        f"PYTHONPATH=.:tests python -m fuzz --profile {'long' if inputs else 'ci'} --seed {seed}"
    )
    assert not unexpected, "\n".join(
        f"{s} ({e['count']}×): {e['message'][:200]}\n  {replay} --only {e['inputs'][0]}"
        for s, e in unexpected.items()
    )
    if not inputs:
        missing = sorted(set(COVERAGE) - set(summary.coverage))
        assert not missing, f"the CI run no longer covers: {missing}"
