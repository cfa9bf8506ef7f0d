"""
The shared test kit: where the repository is, and the builders the tests share.

- ``kit.urdf``: robot texts, one element at a time (links, joints, ``<inertial>`` blocks, boxes,
  cylinders, spheres and meshes as geometry), and a moving link on a base.
- ``kit.moments``: mass and moments of solid boxes, cylinders and spheres, from closed forms.
- ``kit.meshes``: triangles of a box, and the STL and OBJ files written from triangles.

``write`` puts any of them in a file.
"""

from __future__ import annotations

from pathlib import Path

REPO = Path(__file__).resolve().parent.parent.parent
EXAMPLES = REPO / "examples"


def write(path: Path, content: str | bytes) -> Path:
    """``content`` written to ``path`` as is (UTF-8, no newline translation), its folder made."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(content.encode("utf-8") if isinstance(content, str) else content)
    return path
