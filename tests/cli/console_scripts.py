"""The installed console scripts, found without PATH."""

from __future__ import annotations

import shutil
import sys
import sysconfig
from pathlib import Path


def console_script(name: str) -> str:
    """
    The path of the console script ``name`` installed with this Python: in its scripts folder
    (a venv's ``bin``, which need not be on PATH when the tests run), else next to the
    interpreter, else wherever PATH finds it.
    """
    for folder in (sysconfig.get_path("scripts"), str(Path(sys.executable).parent)):
        for file in (name, f"{name}.exe"):
            path = Path(folder, file)
            if path.is_file():
                return str(path)
    found = shutil.which(name)
    assert found is not None, f"the console script {name} is not installed"
    return found
