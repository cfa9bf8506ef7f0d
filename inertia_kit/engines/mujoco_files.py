"""
What MuJoCo refuses while it reads the files, before it compiles anything: the URDF parser's
``<inertial>`` errors and the collision meshes its decoders cannot read.

Also the form every MuJoCo check reports in, :class:`Prediction`, which :func:`.mujoco.events`
words as findings once it knows which refusal MuJoCo meets first.
"""

from __future__ import annotations

import os
import posixpath
from dataclasses import dataclass, field
from typing import Any

from inertia_kit.analysis.links import RobotAnalysis
from inertia_kit.description import model
from inertia_kit.engines.vocabulary import Verdict

# the mesh decoders MuJoCo ships (stl_decoder, obj_decoder, the .msh reader)
DECODERS = (".stl", ".obj", ".msh")
STL_MAX_FACES = 200_000
TENSOR_ORDER = ("ixx", "iyy", "izz", "ixy", "ixz", "iyz")  # the order MuJoCo reads them


@dataclass(frozen=True)
class Prediction:
    """
    One thing MuJoCo does to the model: a refusal (its error, in the order it would raise it)
    or a silent change.

    ``stage`` is the check that finds it (``parse``, ``mesh``, ``body``, ``fuse``, ``minval``;
    ``root``, ``clamp``, ``inertiafromgeom`` for changes); ``message`` is MuJoCo's own text
    without its ``Error:``/``XML Error:`` prefix; ``claim`` is the key fact in a few words (a
    refusal's: what MuJoCo refuses, ``mass 0 kg, below mjMINVAL``; a change's: what
    MuJoCo does, ``fixes the root to the world, dropping 2 kg``); ``detail`` says why, in our
    words, as a sentence with the numbers;
    ``element`` is what MuJoCo names after its message (``{"name": "arm"}`` for a compiled
    element, ``{"tag": "mass", "line": 7}`` for an XML element), ``None`` when it names none;
    ``more`` holds the numbers for the finding's ``expected``.
    """

    verdict: Verdict
    stage: str
    link: str | None
    message: str | None
    claim: str
    detail: str
    source: model.Source | None
    element: dict[str, Any] | None = None
    more: dict[str, Any] = field(default_factory=dict)


def refusal(
    stage: str,
    link: str,
    message: str,
    claim: str,
    detail: str,
    source: model.Source | None,
    element: dict[str, Any] | None = None,
    **more: Any,
) -> Prediction:
    """MuJoCo refuses the model with ``message`` (at ``stage``, about ``link``)."""
    return Prediction(Verdict.REFUSES, stage, link, message, claim, detail, source, element, more)


def change(
    stage: str, link: str, claim: str, detail: str, source: model.Source, **more: Any
) -> Prediction:
    """MuJoCo silently changes ``link`` (it says nothing)."""
    return Prediction(Verdict.CHANGES, stage, link, None, claim, detail, source, None, more)


def parseable(value: model.Number) -> bool:
    """Whether MuJoCo reads the text as a number (it takes nan and inf, with a warning)."""
    if not isinstance(value, model.Invalid):
        return True
    try:
        float(value.text)
    except ValueError:
        return False
    return True


# --- the XML parser -----------------------------------------------------------------------------


def parse_refusals(robot: RobotAnalysis) -> list[Prediction]:
    """``<inertial>`` errors of mjXURDF::Body, link by link in document order."""
    found = []
    for link in robot.links:
        inertial = link.link.inertial
        problem, parent = _repeated(link.link, ("inertial",), "link"), "link"
        if problem is None and inertial is not None:
            problem, parent = _unreadable(inertial, link.link), "inertial"
        if problem is None:
            problem, parent = _repeated(link.link, ("origin", "geometry"), "collision"), "collision"
        if problem is None:
            continue
        message, tag, source = problem
        if message.startswith("repeated"):
            claim = f"a second <{tag}>" + ("" if parent == "link" else f" in its <{parent}>")
            why = f"MuJoCo's URDF parser allows one <{tag}> in a <{parent}>"
        else:
            claim = f"its <{tag}> cannot be read"
            why = f"MuJoCo's URDF parser cannot read the <{tag}> of link `{link.name}`"
        found.append(
            refusal(
                "parse",
                link.name,
                message,
                claim,
                why,
                source,
                {"tag": tag, "line": None if source is None else source.line},
            )
        )
    return found


def _repeated(
    link: model.Link, tags: tuple[str, ...], parent: str
) -> tuple[str, str, model.Source | None] | None:
    """
    MuJoCo's refusal of a second ``<tag>`` in a ``<parent>`` (it allows one; measured:
    ``repeated element: 'inertial'``), at the second one.
    """
    for duplicate in link.duplicates:
        if duplicate.parent == parent and duplicate.tag in tags:
            return f"repeated element: '{duplicate.tag}'", duplicate.tag, duplicate.ignored
    return None


def _unreadable(
    inertial: model.Inertial, link: model.Link
) -> tuple[str, str, model.Source | None] | None:
    """
    MuJoCo's message, the tag it names and where, for the first thing in the ``<inertial>`` it
    cannot read, in the order it reads (measured): a second ``<origin>``, then the ``<mass>``
    (a second one first), then the ``<inertia>`` (likewise).
    """

    def repeated(tag: str) -> tuple[str, str, model.Source | None] | None:
        return _repeated(link, (tag,), "inertial")

    if found := repeated("origin"):
        return found
    if inertial.mass_source is None:
        return "missing element: 'mass'", "inertial", inertial.source
    if found := repeated("mass"):
        return found
    if inertial.mass is None:
        return "required attribute missing: 'value'", "mass", inertial.mass_source
    if not parseable(inertial.mass):
        return "bad format in attribute 'value'", "mass", inertial.mass_source
    if inertial.inertia_source is None:
        return "missing element: 'inertia'", "inertial", inertial.source
    if found := repeated("inertia"):
        return found
    for name in TENSOR_ORDER:
        value = getattr(inertial, name)
        if value is None:
            return f"required attribute missing: '{name}'", "inertia", inertial.inertia_source
        if not parseable(value):
            return f"bad format in attribute '{name}'", "inertia", inertial.inertia_source
    return None


# --- meshes -------------------------------------------------------------------------------------


def mesh_path(robot: model.Robot, filename: str) -> str:
    """
    The file MuJoCo opens for a mesh: the filename joined to the URDF's folder, ``.``/``..``/
    ``//`` reduced; a URI (``package://``, ``file://``) is taken as an absolute path, which no
    file matches.
    """
    if "://" in filename or os.path.isabs(filename):
        return posixpath.normpath(filename)
    folder = os.path.dirname(robot.source.path)
    return (
        posixpath.normpath(posixpath.join(folder, filename))
        if folder
        else (posixpath.normpath(filename))
    )


def _stl_problem(path: str, shown: str) -> str | None:
    """MuJoCo's stl_decoder error for a file, or ``None`` when it reads it."""
    size = os.path.getsize(path)
    if size == 0:
        return f"stl_decoder: STL file '{shown}' is empty"
    if size < 84:
        return f"stl_decoder: invalid header in STL file '{shown}'"
    with open(path, "rb") as stream:
        stream.seek(80)
        faces = int.from_bytes(stream.read(4), "little", signed=True)
    if not 1 <= faces <= STL_MAX_FACES:
        return (
            f"stl_decoder: number of faces should be between 1 and {STL_MAX_FACES} in STL file "
            f"'{shown}'; perhaps this is an ASCII file?"
        )
    if faces * 50 != size - 84:
        return f"stl_decoder: STL file '{shown}' has wrong size; perhaps this is an ASCII file?"
    return None


def mesh_refusals(robot: RobotAnalysis) -> list[Prediction]:
    """
    Collision meshes, in the order MuJoCo makes them assets (links in document order; visual
    meshes are discarded unread: ``discardvisual`` is on for URDF). One asset per file name and
    scale.
    """
    found = []
    seen: set[tuple[str, Any]] = set()
    for link in robot.links:
        for shape in link.link.collisions:
            geometry = shape.geometry
            if not isinstance(geometry, model.Mesh):
                continue
            stem = posixpath.splitext(posixpath.basename(geometry.filename.replace("\\", "/")))[0]
            key = (stem, geometry.scale)
            if key in seen:
                continue
            seen.add(key)
            path = mesh_path(robot.robot, geometry.filename)
            where = f"the collision mesh `{geometry.filename}` of link `{link.name}`"
            if not os.path.isfile(path):
                uri = "://" in geometry.filename
                claim = "collision mesh URI unresolved" if uri else "collision mesh file not found"
                why = (
                    f"MuJoCo resolves no package:// or file:// URI: it cannot open {where}"
                    if uri
                    else f"MuJoCo finds no file beside the URDF for {where}"
                )
                # this message names the file as written (reduced), not joined to the folder
                shown = posixpath.normpath(geometry.filename)
                message, element = f"Error opening file '{shown}'", None
            else:
                ext = posixpath.splitext(path)[1].lower()
                element = {"name": stem}
                if ext not in DECODERS:
                    message = f"no decoder found for mesh file '{path}'"
                    claim = f"no decoder for its {ext or 'extension-less'} collision mesh"
                    why = f"MuJoCo reads STL (binary), OBJ and MSH meshes only, not {where}"
                elif ext == ".stl" and (stl := _stl_problem(path, path)) is not None:
                    message = stl
                    claim = "collision mesh unreadable as binary STL"
                    why = (
                        f"MuJoCo reads binary STL with 1 to {STL_MAX_FACES} faces only: it cannot "
                        f"read {where}"
                    )
                else:
                    continue
            found.append(
                refusal(
                    "mesh",
                    link.name,
                    message,
                    claim,
                    why,
                    geometry.source,
                    element,
                    mesh=geometry.filename,
                )
            )
    return found
