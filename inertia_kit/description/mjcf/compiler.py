"""The ``<compiler>`` settings that bear on mass properties and geometry, as MuJoCo reads them
(every ``<compiler>`` element in order, a later attribute over an earlier one)."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from lxml import etree

from inertia_kit.description import model
from inertia_kit.description.mjcf.defaults import local


@dataclass(frozen=True)
class Compiler:
    degrees: bool = True  # angle="degree", MJCF's default
    eulerseq: str = "xyz"
    meshdir: str | None = None
    assetdir: str | None = None
    autolimits: bool = True
    fitaabb: bool = False  # a primitive fitted to a mesh by its bounding box (not read yet)
    inference: model.Inference = field(default_factory=model.Inference)

    def mesh_folder(self, model_folder: Path) -> Path:
        """Where ``<mesh file>`` names are looked for: ``meshdir``, else ``assetdir``, relative
        to the model's folder unless absolute."""
        folder = self.meshdir if self.meshdir is not None else self.assetdir
        return model_folder if folder is None else model_folder / folder


_TRUE = ("true",)


def read_compiler(root: etree._Element, source_of) -> Compiler:
    """The settings of every ``<compiler>`` under ``root``, later ones over earlier ones."""
    said: dict[str, str] = {}
    source = None
    for element in root:
        if local(element) == "compiler":
            said.update(element.attrib)
            source = source_of(element)

    def number(name: str, default: float) -> float:
        try:
            return float(said[name])
        except (KeyError, ValueError):
            return default

    groups = said.get("inertiagrouprange", "0 5").split()
    try:
        low, high = int(groups[0]), int(groups[1])
    except (IndexError, ValueError):
        low, high = 0, 5
    total = number("settotalmass", -1.0)
    inference = model.Inference(
        from_geometry={"true": "always", "false": "never"}.get(
            said.get("inertiafromgeom", "auto"), "missing"
        ),
        groups=(low, high),
        min_mass=number("boundmass", 0.0),
        min_inertia=number("boundinertia", 0.0),
        balance=said.get("balanceinertia", "false") in _TRUE,
        total_mass=total if total > 0 else None,
        fuse_static=said.get("fusestatic", "false") in _TRUE,
        source=source,
    )
    return Compiler(
        degrees=said.get("angle", "degree") != "radian",
        eulerseq=said.get("eulerseq", "xyz"),
        meshdir=said.get("meshdir"),
        assetdir=said.get("assetdir"),
        autolimits=said.get("autolimits", "true") in _TRUE,
        fitaabb=said.get("fitaabb", "false") in _TRUE,
        inference=inference,
    )
