"""
Scenes (the contract of ``inertia_kit.view.scene``) built by hand for the page's tests: links
with box visuals, their declared and geometry inertias as closed forms (a solid box's principal
moments; its equivalent box is that box), placed where a test wants them.
"""

from __future__ import annotations

import base64
import math

import numpy as np

from kit.meshes import box_triangles

IDENTITY = [1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0, 0, 0, 0, 0, 1.0]


def translation(x: float, y: float, z: float) -> list[float]:
    """A row-major 4×4 translation."""
    return [1.0, 0, 0, x, 0, 1.0, 0, y, 0, 0, 1.0, z, 0, 0, 0, 1.0]


def scaling(sx: float, sy: float, sz: float, at=(0.0, 0.0, 0.0)) -> list[float]:
    """A row-major 4×4 scaling, then a translation to ``at``."""
    return [sx, 0, 0, at[0], 0, sy, 0, at[1], 0, 0, sz, at[2], 0, 0, 0, 1.0]


def unit_cube_mesh(name: str = "cube") -> dict:
    """The cube of side 1 centred on the origin: 8 corners, 12 triangles, base64 as the contract."""
    triangles = box_triangles((1.0, 1.0, 1.0), (-0.5, -0.5, -0.5)).reshape(-1, 3)
    corners, indices = np.unique(triangles, axis=0, return_inverse=True)
    return {
        "positions": base64.b64encode(corners.astype("<f4").tobytes()).decode(),
        "indices": base64.b64encode(indices.reshape(-1).astype("<u4").tobytes()).decode(),
        "triangles": 12,
        "source_triangles": 12,
        "name": name,
    }


def solid_box(mass: float, size, com) -> dict:
    """
    A solid box's mass properties as the contract's ``declared``: its tensor in the link's axes
    (the box's), principal moments m (b² + c²) / 12 ... along the link's axes, and its
    equivalent box from the principal moments (sides √(6 (I_j + I_k − I_i) / m)): the box
    itself.
    """
    a, b, c = size
    moments = [
        mass * (b * b + c * c) / 12,
        mass * (a * a + c * c) / 12,
        mass * (a * a + b * b) / 12,
    ]
    order = sorted(range(3), key=lambda i: moments[i])
    principal = [moments[i] for i in order]
    axes = np.zeros((3, 3))
    for column, i in enumerate(order):
        axes[i, column] = 1.0
    i1, i2, i3 = principal
    box = [
        math.sqrt(6 * (j + k - i) / mass) for i, j, k in ((i1, i2, i3), (i2, i1, i3), (i3, i1, i2))
    ]
    return {
        "mass": mass,
        "com": list(com),
        # in the link's axes: the box's own
        "tensor": dict(zip(("ixx", "iyy", "izz"), moments, strict=True), ixy=0.0, ixz=0.0, iyz=0.0),
        "moments": principal,
        "axes": axes.reshape(-1).tolist(),
        "along": ["xyz"[i] for i in order],
        "box": box,
        "problem": None,
    }


def link(name, parent=None, *, joint=None, world=IDENTITY, size=(0.2, 0.2, 0.2), at=(0, 0, 0),
         declared=None, geometry=None, findings=(), worst=None) -> dict:  # fmt: skip
    """One link record: a box visual of ``size`` centred at ``at`` in its frame."""
    return {
        "name": name,
        "parent": parent,
        "joint": joint,
        "world": list(world),
        "visuals": [{"mesh": 0, "transform": scaling(*size, at=at), "color": None, "kind": "box"}],
        "declared": declared,
        "geometry": geometry,
        "implied_density": None if declared is None else declared["mass"] / math.prod(size),
        "findings": list(findings),
        "worst": worst,
    }


def finding(code: str, message: str, severity: str = "error", line: int = 7) -> dict:
    return {
        "code": code,
        "name": "test-rule",
        "severity": severity,
        "message": message,
        "file": "robot.urdf",
        "line": line,
        "column": 5,
    }


def two_box_scene(scale: float = 1.0) -> dict:
    """
    A base and an arm on a revolute joint, each a 0.2 m cube; the arm's declared box sits
    0.5 m along x from its geometry box (a COM in the wrong place), and it has an error. Every
    length times ``scale``.
    """
    size = (0.2 * scale,) * 3
    base_inertia = solid_box(2.0, size, (0, 0, 0))
    joint = {
        "name": "shoulder",
        "type": "revolute",
        "origin": translation(0, 0, 0.4 * scale),
        "axis": [0, 0, 1],
        "lower": -1.0,
        "upper": 1.0,
    }
    density = 250.0 / scale**3
    geometry = dict(solid_box(2.0, size, (0, 0, 0)), density=density, basis="a solid box")
    return {
        "format": 1,
        "robot": "two_boxes",
        "file": "robot.urdf",
        "links": [
            link(
                "base",
                size=size,
                declared=base_inertia,
                geometry=dict(base_inertia, density=density),
            ),
            link(
                "arm",
                "base",
                joint=joint,
                world=translation(0, 0, 0.4 * scale),
                size=size,
                declared=solid_box(2.0, size, (0.5 * scale, 0, 0)),
                geometry=geometry,
                findings=[finding("IN020", "the COM is 0.5 m from the centroid </script> <!--")],
                worst="error",
            ),
        ],
        "meshes": [unit_cube_mesh()],
        "findings_elsewhere": [finding("IN001", "a robot-level note", "info", 1)],
        "budget": {"triangles": 12, "decimated": False},
    }
