"""
The fuzz harness (issue 19): generated and mutated robots, xacro projects, meshes,
configuration files and file-system layouts through every command and output format, on copies
in a temporary folder, with limits on time and memory, and checks that no run crashes, hangs,
injects a line, writes where it should not, or leaves a partial file.

- ``tree``: an input as a folder tree; ``seeds``, ``robots``, ``meshes``, ``configs``: what an
  input starts from; ``mutate``, ``layouts``: what is done to it;
- ``plan``: the commands each input is run through; ``execute``: one run in a forked process
  with limits; ``checks``: what a run must never do; ``procedures``: plain runs, writers run
  twice, SIGKILLed writers, concurrent writers;
- ``shrink``, ``campaign``: shrinking, reproducers, the summary; ``known``: the failure classes
  issue 19 lists, still open.

In CI: ``tests/fuzz/test_fuzz.py`` (a fixed seed, a few hundred inputs). A long run::

    PYTHONPATH=.:tests python -m fuzz --inputs 50000 --out fuzz-results
    INERTIA_KIT_FUZZ_INPUTS=50000 INERTIA_KIT_FUZZ_SEED=7 python -m pytest tests/fuzz -s
"""
