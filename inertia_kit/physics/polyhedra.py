"""
Functions for triangle soups in (n, 3, 3) float form: the volume integrals of the solid a closed
surface bounds (as :class:`~.volume_moments.VolumeMoments`), and a test that the surface is
closed and consistently wound.

Both are sums over triangles, so they run over fixed-size chunks with no Python loop over faces
and need no vertex merging: each triangle spans a signed tetrahedron with a reference point,
and the tetrahedra of a closed surface add up to its solid.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.lib.stride_tricks import as_strided
from numpy.typing import ArrayLike, NDArray

from inertia_kit.physics.volume_moments import VolumeMoments

# Triangles per chunk. numpy spends about a microsecond per call whatever the array size, and a
# chunk takes ~30 calls, so chunks must be large; but every call streams its operands through
# the caches, and a chunk's working set (~300 bytes per triangle: input records, float32 and
# float64 coordinates, products) must stay in L2. 4096 measured best; 3072 and 6144 ~5 % slower.
CHUNK = 4096


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

    Integrals: each triangle (a, b, c), taken relative to ``origin``, spans a tetrahedron with
    signed volume ``det/6`` (``det = a · (b × c)``), first moment ``det/24 · s`` and second
    moment ``det/120 · (a aᵀ + b bᵀ + c cᵀ + s sᵀ)`` with ``s = a + b + c``. In terms of the
    edge sums ``u, v, w = a + b, b + c, c + a`` these are ``[u, v, w] = 2 det``, ``u + v + w =
    2 s`` and ``u uᵀ + v vᵀ + w wᵀ = a aᵀ + b bᵀ + c cᵀ + s sᵀ``: three outer products where
    the vertices take four. With rows ``(1, x, y, z)`` over the slots u, v, w of every
    triangle, volume, first and second moment are one matrix product ``(2 det · Q) Qᵀ``.

    Closure: a surface is closed and consistently wound exactly when every directed edge a→b is
    matched by an edge b→a. With pseudo-random 32-bit hashes h and g of each vertex's exact
    coordinate bits, the wrapping sum over all directed edges of h(a)·g(b) - h(b)·g(a) is zero
    for such a surface, however the hashes fall, and for any other surface zero only by a
    chance of about 2⁻³¹ (why one fingerprint: see ``_K_COORDINATE``): an O(n) check with no
    vertex merging.
    Vertices are compared by their exact bits, as STL writers repeat a shared vertex's
    coordinates verbatim; ``x + 0.0`` first turns -0.0 into +0.0 and leaves every other value
    as it is. A triangle (v0, v1, v2) adds ``Σ_j g(v_j) · (h(v_{j-1}) - h(v_{j+1}))``, its
    three edges' share.

    Hashes, in native 32-bit SIMD arithmetic: each coordinate's float32 bit pattern gets a mix
    of its own (``w ^= w >> 16; w *= K; w ^= w >> 15``, a bijection) and h is the sum of the
    three; ``g = h ^ (h >> 15)``. The first right shift is there because CAD coordinates often
    end in a dozen zero mantissa bits, which multiplication alone never carries into the low
    bits; the last one because without it, for such coordinates, h would be linear in a grid's
    indices, and so collide along a lattice, and sums of hashes round a hole would cancel
    whenever its vertices sum alike. A multiply-xor chain over the raw words collapsed a 128³
    grid of integers to 2¹⁵ distinct hashes; this mix gives the ~500 collisions of a random
    function, on integer, millimetre and random grids alike, and fingerprints whose low 16 and
    20 bits are zero as often as uniform random ones.

    Float64 triangles hash their float32 rounding, with any residual folded in: a value that is
    exactly a float32 hashes as in a float32 chunk, so chunks of either type can be mixed.

    Speed (``benchmarks/run.py``): numpy arithmetic on arrays this size is bound by the L2
    cache's bandwidth and by a fixed cost per call, so each chunk runs about 30 calls on
    buffers allocated once per chunk size (allocating temporaries dominates otherwise), laid out
    so that each call covers all vertices or all coordinates, and aligned to pages (numpy's own
    16-byte alignment makes AVX-512 loads straddle cache lines, which halves the throughput).
    """

    def __init__(self, origin: ArrayLike):
        point = np.array(origin, dtype=np.float64)
        if point.shape != (3,) or not np.isfinite(point).all():
            raise ValueError(f"origin must be a finite (3,) point, got {origin!r}")
        self.origin = point
        self.count = 0
        # (2 det · Q) Qᵀ: [0, 0] = 6 Σ det, [0, 1:] = 4 Σ det s,
        # [1:, 1:] = 2 Σ det (a aᵀ + b bᵀ + c cᵀ + s sᵀ)
        self._sums = np.zeros((4, 4))
        self._fingerprint = np.zeros(1, dtype=np.uint32)
        self._low = np.full(3, np.inf)
        self._high = np.full(3, -np.inf)
        self._plans: dict[tuple[int, np.dtype], _Plan] = {}

    def add(self, triangles: NDArray) -> None:
        """
        Add triangles, in chunks of at most :data:`CHUNK`.

        Parameters
        ----------
        triangles : (n, 3, 3) float32 or float64
          Any strides (a view into STL records works as is).
        """
        tris = as_triangles(triangles)
        for start in range(0, len(tris), CHUNK):
            chunk = tris[start : start + CHUNK]
            key = (len(chunk), chunk.dtype)
            plan = self._plans.get(key)
            if plan is None:
                if len(self._plans) > 2:  # keep the buffers of a few chunk sizes at most
                    self._fold()
                plan = self._plans[key] = _Plan(self, *key)
            plan.run(chunk)
            self.count += len(chunk)

    def _fold(self) -> None:
        """Bring the totals up to date, and free the chunk buffers (~300 bytes a triangle)."""
        for plan in self._plans.values():
            plan.fold()
        self._plans.clear()

    @property
    def closed(self) -> bool:
        """Every directed edge is matched by its reverse: closed and consistently wound."""
        self._fold()
        return self.count > 0 and not self._fingerprint.any()

    @property
    def bounds(self) -> NDArray[np.float64]:
        """(2, 3) lowest and highest vertex coordinates, m."""
        self._fold()
        return np.array([self._low, self._high])

    @property
    def moments(self) -> VolumeMoments:
        self._fold()
        sums = self._sums
        second = sums[1:, 1:]
        return VolumeMoments(
            sums[0, 0] / 36.0,
            sums[0, 1:] / 96.0,
            (second + second.T) / 480.0,
            self.origin.copy(),
        )


# One 32-bit fingerprint: an open or inconsistently wound surface passes as closed with a chance
# of about 2⁻³¹ (5e-10; measured: the fingerprint's low 16 and 20 bits are as often zero as a
# uniform random value's), so that its integrals are taken as exact instead of being repaired;
# a closed surface is never called open. A second, independent fingerprint (2⁻⁶²) measured 5 %
# slower end to end, a third of the margin over the 20 M triangles/s target: not worth it.
_K_COORDINATE = np.array([[0x9E3779B1], [0x85EBCA77], [0xC2B2AE3D]], dtype=np.uint32)
_K_RESIDUAL = np.array(0x9E3779B97F4A7C15, dtype=np.uint64)
_S15 = np.array(15, dtype=np.uint32)
_S16 = np.array(16, dtype=np.uint32)
_S32 = np.array(32, dtype=np.uint64)
_ZERO32 = np.array(0.0, dtype=np.float32)
_ZERO64 = np.array(0.0)
# chunks whose small results (fingerprint, bounds, the 4×4 sums) are kept in tables and added
# up together: adding such tiny arrays costs as much as a ufunc call over a whole chunk
_ROWS = 64

add, sub, mul, xor, shr = np.add, np.subtract, np.multiply, np.bitwise_xor, np.right_shift


class _Plan:
    """
    The buffers for chunks of ``size`` triangles of one dtype, and every view the numpy calls
    of a chunk work on, made once: slicing an array costs as much as a small ufunc call.
    """

    def __init__(self, owner: SurfaceIntegrator, size: int, dtype: np.dtype):
        n = size
        self.owner = owner
        # the chunk's coordinates as they came, coordinate-major: (coordinate, vertex, triangle)
        p = _aligned((3, 3, n), dtype)
        flat = p.reshape(-1)
        if dtype == np.float32:
            words = flat.view(np.uint32)
            self.float64 = None
        else:
            words = _aligned((9 * n,), np.uint32)
            self.float64 = (
                _aligned((9 * n,), np.float32),
                _aligned((9 * n,), np.uint64),
                _aligned((9 * n,), np.uint64),
                words,
            )
        # rows (1, x, y, z, x, y) by slots (u, v, w): x and y again for the cross products
        q = _aligned((6, 3, n))
        q[0] = 1.0
        # rows (2 det, 2 det x, 2 det y, 2 det z) by slots; before that, scratch space for
        # the hashes and then for the chunk's coordinates in float64
        weighted = _aligned((4, 3, n))
        scratch = weighted.reshape(-1)
        mixed = scratch.view(np.uint32)[: 9 * n]  # (coordinate, vertex, triangle)
        hashes = scratch.view(np.uint32)[18 * n : 23 * n].reshape(5, n)  # vertices 2 0 1 2 0
        p64 = scratch[: 9 * n].reshape(3, 3, n)
        products = scratch[3 * n : 9 * n].reshape(2, 3, n)
        uvw = q[1:4]
        row = q.strides[0]
        self.p = p
        self.hash_views = (
            flat,
            _ZERO32 if dtype == np.float32 else _ZERO64,
            words,
            mixed,
            mixed.reshape(3, 3 * n),
            scratch.view(np.uint32)[9 * n : 18 * n],
            mixed[: 3 * n],
            mixed[3 * n : 6 * n],
            mixed[6 * n :],
            hashes[1:4].reshape(-1),  # h
            hashes[0::4],  # rows 0 and 4 ...
            hashes[3::-2],  # ... are copies of rows 3 and 1
            hashes[0:3].reshape(-1),  # h(v_{j-1})
            hashes[2:5].reshape(-1),  # h(v_{j+1})
            scratch.view(np.uint32)[: 3 * n],  # h(v_{j-1}) - h(v_{j+1}), then g times that
            scratch.view(np.uint32)[3 * n : 6 * n],  # g
            p.reshape(3, 3 * n),
        )
        self.integral_views = (
            p,
            p64,
            p64[:, 0:2],  # a, b
            p64[:, 1:3],  # b, c
            p64[:, 2],  # c
            p64[:, 0],  # a
            2.0 * owner.origin[:, None, None],
            uvw[:, 0:2],
            uvw[:, 2],
            uvw,
            q[4:, 1:3],
            q[1:3, 1:3],
            # v rows (y z x) and (z x y), w rows (z x y) and (y z x): v × w = products[0] -
            # products[1], the three rows at once
            as_strided(q[2:, 1], (2, 3, n), (row, row, q.strides[2]), writeable=False),
            as_strided(q[3:, 2], (2, 3, n), (-row, row, q.strides[2]), writeable=False),
            products,
            products[0],
            products[1],
            uvw[:, 0],
            weighted[0, 0],  # 2 det
            weighted[0, 1:],
            weighted[0],
            weighted[1:],
            weighted.reshape(4, 3 * n),
            q[:4].reshape(4, 3 * n).T,
        )
        # each chunk's fingerprint, bounds and sums go to a row of these tables
        self.rows = 0
        self.tables = (
            np.empty(_ROWS, dtype=np.uint32),
            np.empty((_ROWS, 3), dtype),
            np.empty((_ROWS, 3), dtype),
            np.empty((_ROWS, 4, 4)),
        )
        self.outputs: list[tuple[NDArray, ...] | None] = [None] * _ROWS  # row views, as needed

    def run(self, triangles: NDArray) -> None:
        """Integrate a chunk of exactly ``size`` triangles."""
        outputs = self.outputs[self.rows]
        if outputs is None:
            outputs = self.outputs[self.rows] = tuple(t[self.rows, ...] for t in self.tables)
        fingerprint, low, high, sums = outputs
        (
            flat, zero, words, mixed, by_coordinate, shifted, mixed_x, mixed_y, mixed_z,
            h, wrap_to, wrap_from, h_before, h_after, f, g, per_coordinate,
        ) = self.hash_views  # fmt: skip
        add(triangles.transpose(2, 1, 0), zero, self.p)  # -0.0 + 0.0 = +0.0
        if self.float64 is not None:
            _float64_words(flat, *self.float64)

        # h: each coordinate's bits mixed on their own, summed
        shr(words, _S16, mixed)
        xor(words, mixed, mixed)
        mul(by_coordinate, _K_COORDINATE, by_coordinate)
        shr(mixed, _S15, shifted)
        xor(mixed, shifted, mixed)
        add(mixed_x, mixed_y, h)
        add(h, mixed_z, h)
        # the fingerprint: Σ_j g(v_j) (h(v_{j-1}) - h(v_{j+1})), g = h ^ (h >> 15)
        np.copyto(wrap_to, wrap_from)
        sub(h_before, h_after, f)
        shr(h, _S15, g)
        xor(h, g, g)
        mul(g, f, f)
        add.reduce(f, 0, np.uint32, fingerprint)
        np.minimum.reduce(per_coordinate, 1, None, low)
        np.maximum.reduce(per_coordinate, 1, None, high)

        (
            p, p64, ab, bc, c, a, origin2, uv, w, uvw, xy_to, xy_from,
            v_rows, w_rows, products, cross, term, u, det, det_copies, dets, weighted, left, right,
        ) = self.integral_views  # fmt: skip
        # u, v, w = a + b, b + c, c + a about the origin (a + b of float32s is exact in float64)
        np.copyto(p64, p)
        add(ab, bc, uv)
        add(c, a, w)
        sub(uvw, origin2, uvw)
        np.copyto(xy_to, xy_from)
        # 2 det = u · (v × w)
        mul(v_rows, w_rows, products)
        sub(cross, term, cross)
        np.einsum("in,in->n", u, cross, out=det)
        np.copyto(det_copies, det)
        # volume, first and second moment: one matrix product
        mul(uvw, dets, weighted)
        np.matmul(left, right, sums)
        self.rows += 1
        if self.rows == _ROWS:
            self.fold()

    def fold(self) -> None:
        """Add the tables' rows so far to the integrator's totals."""
        k, self.rows = self.rows, 0
        if k:
            owner = self.owner
            fingerprints, lows, highs, sums = (table[:k] for table in self.tables)
            owner._fingerprint += fingerprints.sum(axis=0, dtype=np.uint32)
            np.minimum(owner._low, lows.min(axis=0), out=owner._low)
            np.maximum(owner._high, highs.max(axis=0), out=owner._high)
            owner._sums += sums.sum(axis=0)


def _float64_words(
    values: NDArray, single: NDArray, residual: NDArray, shifted: NDArray, out: NDArray
) -> None:
    """
    32-bit words of float64 coordinates: the bits of their float32 rounding, XOR a 64 → 32-bit
    multiplicative hash of the rounding residual's bits (0 for a value that is a float32, which
    thus hashes as one). The residual's high half is folded into its low half before the
    multiplication: negating x flips the sign bits of both its rounding and its residual, and
    without the fold those two flips cancel, so that x and -x hash alike.
    """
    # beyond float32's range (3.4e38) the rounding is ±inf: such a surface is refused later as
    # overflowing (MeshError), its words only need to exist
    with np.errstate(over="ignore", invalid="ignore"):
        np.copyto(single, values, casting="same_kind")
        sub(values, single, residual.view(np.float64))
    shr(residual, _S32, shifted)
    xor(residual, shifted, residual)
    mul(residual, _K_RESIDUAL, residual)
    shr(residual, _S32, residual)
    xor(single.view(np.uint32), residual.view(np.uint32)[::2], out)


def _aligned(shape: tuple[int, ...], dtype: np.dtype | type = np.float64) -> NDArray:
    """An uninitialised array that starts on a page boundary."""
    dtype = np.dtype(dtype)
    nbytes = math.prod(shape) * dtype.itemsize
    raw = np.empty(nbytes + 4096, dtype=np.uint8)
    start = -raw.ctypes.data % 4096
    return raw[start : start + nbytes].view(dtype).reshape(shape)


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
    integrator.add(tris)
    return integrator
