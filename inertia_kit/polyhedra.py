"""
Functions for triangle soups in (n, 3, 3) float form: the volume integrals of the solid a closed
surface bounds, and a test that the surface is closed and consistently wound.

Both are sums over triangles, so they run over fixed-size chunks with no Python loop over faces
and need no vertex merging: each triangle spans a signed tetrahedron with a reference point,
and the tetrahedra of a closed surface add up to its solid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from inertia_kit.mass import MassProperties, inertia_from_second_moment
from inertia_kit.primitives import body_mass

# triangles per chunk: large enough to amortise numpy's per-call cost, small enough that a
# chunk's float64 working set (~12 KB per 128 triangles) stays in the CPU caches
CHUNK = 12288


@dataclass(frozen=True, eq=False)
class VolumeMoments:
    """
    Signed volume integrals of the solid bounded by a triangle surface, about ``origin``.

    A surface wound inside-out has a negative ``volume``; an open surface has moments that
    depend on ``origin`` and mean nothing.

    Attributes
    ----------
    volume : float
      ``∫ dV``, m³
    first : (3,) float
      ``∫ (x - origin) dV``, m⁴
    second : (3, 3) float
      ``∫ (x - origin)(x - origin)ᵀ dV``, m⁵
    origin : (3,) float
      The reference point, m. Integrating about a point near the surface keeps the central
      second moment free of cancellation for parts far from the coordinate origin.
    """

    volume: float
    first: NDArray[np.float64]
    second: NDArray[np.float64]
    origin: NDArray[np.float64]

    def __add__(self, other: VolumeMoments) -> VolumeMoments:
        if not np.array_equal(self.origin, other.origin):
            other = other.about(self.origin)
        return VolumeMoments(
            self.volume + other.volume,
            self.first + other.first,
            self.second + other.second,
            self.origin,
        )

    def about(self, origin: ArrayLike) -> VolumeMoments:
        """The same integrals about another reference point."""
        d = self.origin - np.asarray(origin, dtype=np.float64)
        first = self.first + self.volume * d
        second = self.second + np.outer(self.first, d) + np.outer(d, self.first) + self.volume * np.outer(d, d)
        return VolumeMoments(self.volume, first, second, np.asarray(origin, dtype=np.float64))

    def negated(self) -> VolumeMoments:
        """The integrals of the same surface wound the other way."""
        return VolumeMoments(-self.volume, -self.first, -self.second, self.origin)

    def scaled(self, scale: ArrayLike) -> VolumeMoments:
        """
        The integrals after scaling every vertex by ``diag(scale)`` about the coordinate origin.

        A negative scale mirrors the solid; its volume stays positive, as URDF means it.
        """
        s = np.asarray(scale, dtype=np.float64)
        if s.shape != (3,) or not np.all(np.isfinite(s)) or np.any(s == 0):
            raise ValueError(f"scale must be three finite non-zero factors, got {scale!r}")
        jacobian = abs(float(np.prod(s)))
        return VolumeMoments(
            jacobian * self.volume,
            jacobian * s * self.first,
            jacobian * np.outer(s, s) * self.second,
            s * self.origin,
        )

    @property
    def centroid(self) -> NDArray[np.float64]:
        """(3,) centroid of the solid, m."""
        return self.origin + self.first / self.volume

    def mass_properties(
        self, *, density: float | None = None, mass: float | None = None
    ) -> MassProperties:
        """
        Mass properties of the solid at uniform density (exactly one of ``density``, ``mass``).

        Raises ``ValueError`` unless the volume is positive: an inverted or empty surface has no
        honest mass properties, and the caller decides what to report.
        """
        if not self.volume > 0:
            raise ValueError(f"the surface bounds no positive volume ({self.volume} m³)")
        m = body_mass(self.volume, density, mass)
        offset = self.first / self.volume
        central = self.second - self.volume * np.outer(offset, offset)
        return MassProperties(
            m, self.origin + offset, inertia_from_second_moment(central * (m / self.volume))
        )


def as_triangles(triangles: ArrayLike) -> NDArray:
    """Coerce to an (n, 3, 3) float array (float32 kept as is), raising on any other shape."""
    array = np.asarray(triangles)
    if array.dtype not in (np.float32, np.float64):
        array = array.astype(np.float64)
    if array.ndim != 3 or array.shape[1:] != (3, 3):
        raise ValueError(f"triangles must be (n, 3, 3), got shape {array.shape}")
    return array


class SurfaceIntegrator:
    """
    Accumulates, chunk by chunk, the volume integrals of a triangle surface, a closure
    fingerprint and the bounding box of its vertices.

    Each triangle (a, b, c), taken relative to ``origin``, spans a tetrahedron with signed volume
    ``det/6`` (``det = a · (b × c)``), first moment ``det/24 · s`` and second moment
    ``det/120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ)`` with ``s = a + b + c``; the second moments of a
    whole chunk are one matrix product.

    Closure: a surface is closed and consistently wound exactly when every directed edge a→b is
    matched by an edge b→a. With pseudo-random 64-bit hashes h, g of each vertex's exact
    coordinates, the wrapping sum over all directed edges of h(a)·g(b) - h(b)·g(a) is zero for
    such a surface, and for any other surface zero only by a chance of order 2⁻⁶⁰: an O(n) check
    with no vertex merging. Vertices are compared by their exact bits, as STL writers repeat a
    shared vertex's coordinates verbatim.

    Every array operation writes into buffers allocated once per chunk size: on this kind of
    work numpy spends more time allocating temporaries than computing.
    """

    def __init__(self, origin: ArrayLike):
        point = np.array(origin, dtype=np.float64)
        if point.shape != (3,) or not np.isfinite(point).all():
            raise ValueError(f"origin must be a finite (3,) point, got {origin!r}")
        # x - o maps -0.0 and +0.0 to the same bits unless o is zero: keep o away from zero so
        # the closure hashes see one zero
        point[point == 0.0] = np.finfo(np.float64).tiny
        self.origin = point
        self.count = 0
        self._det_sum = 0.0
        self._first = np.zeros(3)
        self._second = np.zeros((3, 3))
        self._imbalance = 0
        self._low = np.full(3, np.inf)
        self._high = np.full(3, -np.inf)
        self._size = -1

    def _buffers(self, n: int) -> None:
        if n == self._size:
            return
        self._size = n
        self._q = np.empty((3, 4, n))  # coordinate, (a, b, c, s), triangle
        self._w = np.empty((3, 4, n))
        self._det = np.empty(n)
        self._f = np.empty((2, n))
        self._h = np.empty((3, n), dtype=np.uint64)
        self._g = np.empty((3, n), dtype=np.uint64)
        self._t = np.empty((3, n), dtype=np.uint64)
        self._e = np.empty((2, n), dtype=np.uint64)

    def add(self, triangles: NDArray) -> None:
        """
        Add a chunk of triangles.

        Parameters
        ----------
        triangles : (n, 3, 3) float32 or float64
          Any strides (a view into STL records works as is).
        """
        n = len(triangles)
        if n == 0:
            return
        self._buffers(n)
        q, w, det, f = self._q, self._w, self._det, self._f
        # one pass: transpose to coordinate-major, widen to float64, move to the origin
        np.subtract(triangles.transpose(2, 1, 0), self.origin[:, None, None], out=q[:, :3])
        np.add(q[:, 0], q[:, 1], out=q[:, 3])
        q[:, 3] += q[:, 2]
        np.minimum(self._low, q[:, :3].min(axis=(1, 2)) + self.origin, out=self._low)
        np.maximum(self._high, q[:, :3].max(axis=(1, 2)) + self.origin, out=self._high)

        (ax, bx, cx, _), (ay, by, cy, _), (az, bz, cz, _) = q
        cross, term = f
        np.multiply(by, cz, out=cross)
        np.multiply(bz, cy, out=term)
        cross -= term
        np.multiply(ax, cross, out=det)
        np.multiply(bz, cx, out=cross)
        np.multiply(bx, cz, out=term)
        cross -= term
        cross *= ay
        det += cross
        np.multiply(bx, cy, out=cross)
        np.multiply(by, cx, out=term)
        cross -= term
        cross *= az
        det += cross

        np.multiply(q.reshape(12, n), det, out=w.reshape(12, n))
        self._det_sum += float(det.sum())
        self._first += q[:, 3] @ det
        self._second += w.reshape(3, 4 * n) @ q.reshape(3, 4 * n).T
        self._imbalance = (self._imbalance + self._edge_imbalance()) & 0xFFFFFFFFFFFFFFFF
        self.count += n

    def _edge_imbalance(self) -> int:
        bits = self._q[:, :3].view(np.uint64)  # coordinate, vertex, triangle
        h, g, t, e = self._h, self._g, self._t, self._e
        with np.errstate(over="ignore"):
            np.multiply(bits[0], _K0, out=h)
            np.multiply(bits[1], _K1, out=t)
            h ^= t
            np.multiply(bits[2], _K2, out=t)
            h ^= t
            np.right_shift(h, _S32, out=t)
            h ^= t
            h *= _M1
            np.multiply(h, _M2, out=g)
            np.right_shift(g, _S32, out=t)
            g ^= t
            total, term = e
            # Σ over the triangle's edges a→b of h(a)g(b) - h(b)g(a)
            np.multiply(h[0], g[1], out=total)
            np.multiply(h[1], g[0], out=term)
            total -= term
            np.multiply(h[1], g[2], out=term)
            total += term
            np.multiply(h[2], g[1], out=term)
            total -= term
            np.multiply(h[2], g[0], out=term)
            total += term
            np.multiply(h[0], g[2], out=term)
            total -= term
            return int(total.sum(dtype=np.uint64))

    @property
    def closed(self) -> bool:
        """Every directed edge is matched by its reverse: closed and consistently wound."""
        return self.count > 0 and self._imbalance == 0

    @property
    def bounds(self) -> NDArray[np.float64]:
        """(2, 3) lowest and highest vertex coordinates, m."""
        return np.array([self._low, self._high])

    @property
    def moments(self) -> VolumeMoments:
        return VolumeMoments(
            self._det_sum / 6.0, self._first / 24.0, self._second / 120.0, self.origin.copy()
        )


_K0 = np.uint64(0x9E3779B97F4A7C15)
_K1 = np.uint64(0xC2B2AE3D27D4EB4F)
_K2 = np.uint64(0x165667B19E3779F9)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S32 = np.uint64(32)


def reference_point(triangles: NDArray) -> NDArray[np.float64]:
    """A reference point near the surface: the mean of (at most) the first chunk's vertices."""
    head = np.asarray(triangles[:CHUNK], dtype=np.float64)
    return head.reshape(-1, 3).mean(axis=0) if len(head) else np.zeros(3)


def integrate(triangles: ArrayLike, origin: ArrayLike | None = None) -> SurfaceIntegrator:
    """
    Integrate a whole triangle soup in chunks.

    Parameters
    ----------
    triangles : (n, 3, 3) float
      Vertices of each triangle, counter-clockwise seen from outside, m.
    origin : (3,) float, optional
      Reference point; default: near the surface (see :func:`reference_point`).
    """
    tris = as_triangles(triangles)
    integrator = SurfaceIntegrator(reference_point(tris) if origin is None else origin)
    for start in range(0, len(tris), CHUNK):
        integrator.add(tris[start : start + CHUNK])
    return integrator


def volume_moments(triangles: ArrayLike, origin: ArrayLike | None = None) -> VolumeMoments:
    """Volume integrals of the solid bounded by a triangle soup (see :func:`integrate`)."""
    return integrate(triangles, origin).moments
