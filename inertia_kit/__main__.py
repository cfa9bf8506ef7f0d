"""``python -m inertia_kit``: the ``inertia-kit`` command, for when its script is not on PATH."""

from inertia_kit.cli import main

if __name__ == "__main__":
    main(prog_name="inertia-kit")
