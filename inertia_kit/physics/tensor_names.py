"""
The six attribute names of a URDF/SDFormat inertia tensor and their places in the 3×3 matrix.

One home for this vocabulary: the loader reads these attributes, the writer writes them, the
rules and messages name them. Products use the tensor convention ``ixy = -∫xy dm`` (DESIGN.md).
"""

from __future__ import annotations

#: The order URDF writes them in ``<inertia ixx ixy ixz iyy iyz izz/>``.
TENSOR: tuple[str, ...] = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
DIAGONAL: tuple[str, ...] = ("ixx", "iyy", "izz")
PRODUCTS: tuple[str, ...] = ("ixy", "ixz", "iyz")
#: attribute -> (row, column) in the symmetric 3×3 tensor
INDEX: dict[str, tuple[int, int]] = {
    "ixx": (0, 0),
    "ixy": (0, 1),
    "ixz": (0, 2),
    "iyy": (1, 1),
    "iyz": (1, 2),
    "izz": (2, 2),
}
