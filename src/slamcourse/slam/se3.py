"""Rotations and rigid motions in 3-D: SO(3), SE(3), their exp/log maps, and a 3-D pose graph.

Conventions (stated once for chapter ``se3``):

- a rotation is a 3×3 matrix ``R`` (``Rᵀ R = I``, ``det R = 1``); a rotation vector ``w = θ n``
  (unit axis ``n``, angle ``θ ∈ [0, π]``) is its logarithm, ``R = Exp(w)``;
- a unit quaternion is written ``(qw, qx, qy, qz)``; ``q`` and ``−q`` are the same rotation;
- a pose is a 4×4 homogeneous matrix ``T = [[R, t], [0, 1]]`` mapping the body frame to the
  world; a tangent vector of SE(3) is ``ξ = (ρ, φ)``: translation part first, rotation second;
- the update is the right perturbation ``x ⊞ δ = x · Exp(δ)``;
- an edge ``(i, j, Z, Ω)`` measures pose ``j`` seen from pose ``i``; its error is
  ``e = (t_E, Log R_E)`` of ``E = Z⁻¹ X_i⁻¹ X_j`` (translation, then rotation vector), and
  ``χ² = Σ eᵀ Ω e``;
- TORO/iSAM ``EDGE3 i j x y z roll pitch yaw s11 … s66`` lines: the rotation is
  ``Rz(yaw) Ry(pitch) Rx(roll)``, the translation is in pose ``i``'s frame, and the 21 numbers
  are the upper triangle, row by row, of the square-root information ``S`` (``Ω = Sᵀ S``).
  Both were checked against ``sphere2500``'s ground truth (tests/unit/test_slam_se3.py).

Batched functions take stacks (``(m, 3)`` vectors, ``(m, 3, 3)`` matrices) so that a graph of
thousands of edges is handled by numpy in one call.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]

SMALL = 1e-4
"""Below this angle (radians) the exp/log/Jacobian coefficients use their Taylor series."""
NEAR_PI = 0.1
"""Within this of π, ``so3_log`` reads the axis from the symmetric part of ``R``."""


# --- SO(3) --------------------------------------------------------------------------------------


def hat(w: ArrayLike) -> Array:
    """The skew-symmetric matrix ``[w]×`` with ``[w]× v = w × v``; ``(…, 3)`` → ``(…, 3, 3)``."""
    v = np.asarray(w, dtype=float)
    out = np.zeros((*v.shape[:-1], 3, 3))
    out[..., 0, 1], out[..., 0, 2] = -v[..., 2], v[..., 1]
    out[..., 1, 0], out[..., 1, 2] = v[..., 2], -v[..., 0]
    out[..., 2, 0], out[..., 2, 1] = -v[..., 1], v[..., 0]
    return out


def vee(m: ArrayLike) -> Array:
    """The vector of the antisymmetric part: ``vee([w]×) = w``; ``(…, 3, 3)`` → ``(…, 3)``."""
    a = np.asarray(m, dtype=float)
    return 0.5 * np.stack(
        [a[..., 2, 1] - a[..., 1, 2], a[..., 0, 2] - a[..., 2, 0], a[..., 1, 0] - a[..., 0, 1]],
        axis=-1,
    )


def _coefficients(theta: Array) -> tuple[Array, Array, Array]:
    """``sin θ/θ``, ``(1 − cos θ)/θ²`` and ``(θ − sin θ)/θ³``, by series below :data:`SMALL`."""
    small = theta < SMALL
    t = np.where(small, 1.0, theta)
    t2 = theta * theta
    a = np.where(small, 1 - t2 / 6 + t2 * t2 / 120, np.sin(t) / t)
    b = np.where(small, 0.5 - t2 / 24 + t2 * t2 / 720, (1 - np.cos(t)) / (t * t))
    c = np.where(small, 1 / 6 - t2 / 120 + t2 * t2 / 5040, (t - np.sin(t)) / (t * t * t))
    return a, b, c


def so3_exp(w: ArrayLike) -> Array:
    """Rodrigues' formula ``R = I + (sin θ/θ) K + ((1 − cos θ)/θ²) K²`` with ``K = [w]×``.

    ``w``: rotation vector(s), ``(3,)`` or ``(m, 3)``; returns ``(3, 3)`` or ``(m, 3, 3)``.
    """
    v = np.asarray(w, dtype=float)
    theta = np.linalg.norm(v, axis=-1)
    a, b, _ = _coefficients(theta)
    k = hat(v)
    eye = np.broadcast_to(np.eye(3), k.shape)
    out: Array = eye + a[..., None, None] * k + b[..., None, None] * (k @ k)
    return out


def so3_log(r: ArrayLike) -> Array:
    """The rotation vector ``w`` (``|w| = θ ∈ [0, π]``) with ``Exp(w) = R``; ``(…, 3, 3)`` →
    ``(…, 3)``.

    ``θ = atan2(sin θ, cos θ)`` from the antisymmetric part and the trace (accurate everywhere,
    unlike ``acos`` of the trace near 0 and π). Away from π the axis is the antisymmetric part
    over ``sin θ`` (a series for small θ). Within :data:`NEAR_PI` of π that part vanishes, so
    the axis is read from the symmetric part ``(R + Rᵀ)/2 − cos θ I = (1 − cos θ) n nᵀ`` (its
    largest diagonal entry's column) and only its sign from the antisymmetric part. At exactly
    π (``R`` symmetric) both ``±π n`` are logarithms: the one whose largest-magnitude component
    (the first of equal ones) is positive is returned.
    """
    m = np.asarray(r, dtype=float)
    axis_part = vee(m)  # sin θ · n
    s = np.linalg.norm(axis_part, axis=-1)
    c = (np.trace(m, axis1=-2, axis2=-1) - 1) / 2
    theta = np.arctan2(s, c)
    small = theta < SMALL
    safe_s = np.where(small | (s == 0), 1.0, s)
    t2 = theta * theta
    factor = np.where(small, 1 + t2 / 6 + 7 * t2 * t2 / 360, theta / safe_s)
    w = factor[..., None] * axis_part
    near = theta > math.pi - NEAR_PI
    if np.any(near):
        sym = (m[near] + np.swapaxes(m[near], -1, -2)) / 2 - c[near, None, None] * np.eye(3)
        diag = np.diagonal(sym, axis1=-2, axis2=-1)
        k = np.argmax(diag, axis=-1)
        rows = np.arange(len(k))
        column = sym[rows, :, k]
        n = column / np.linalg.norm(column, axis=-1, keepdims=True)
        sign = np.sign(np.einsum("ki,ki->k", n, axis_part[near]))
        n *= np.where(sign < 0, -1.0, 1.0)[:, None]
        w[near] = theta[near, None] * n
    out: Array = w
    return out


def right_jacobian(w: ArrayLike) -> Array:
    """``J_r(w) = I − ((1 − cos θ)/θ²) K + ((θ − sin θ)/θ³) K²``, so that
    ``Exp(w + δ) ≈ Exp(w) Exp(J_r δ)``."""
    v = np.asarray(w, dtype=float)
    _, b, c = _coefficients(np.linalg.norm(v, axis=-1))
    k = hat(v)
    out: Array = np.eye(3) - b[..., None, None] * k + c[..., None, None] * (k @ k)
    return out


def right_jacobian_inverse(w: ArrayLike) -> Array:
    """``J_r(w)⁻¹ = I + ½ K + (1/θ² − (1 + cos θ)/(2 θ sin θ)) K²``: ``Log(Exp(w) Exp(δ)) ≈ w +
    J_r⁻¹ δ``. Defined for ``θ < π`` (the coefficient's series is used for small ``θ``)."""
    v = np.asarray(w, dtype=float)
    theta = np.linalg.norm(v, axis=-1)
    small = theta < SMALL
    t = np.where(small, 1.0, theta)
    t2 = theta * theta
    d = np.where(small, 1 / 12 + t2 / 720, 1 / (t * t) - (1 + np.cos(t)) / (2 * t * np.sin(t)))
    k = hat(v)
    out: Array = np.eye(3) + 0.5 * k + d[..., None, None] * (k @ k)
    return out


def rpy_matrix(roll: ArrayLike, pitch: ArrayLike, yaw: ArrayLike) -> Array:
    """``Rz(yaw) Ry(pitch) Rx(roll)``: the TORO/iSAM/GTSAM ``EDGE3`` convention."""
    r, p, y = (np.asarray(a, dtype=float) for a in (roll, pitch, yaw))
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    out = np.empty((*np.shape(r), 3, 3))
    out[..., 0, 0], out[..., 0, 1], out[..., 0, 2] = (
        cy * cp,
        cy * sp * sr - sy * cr,
        cy * sp * cr + sy * sr,
    )
    out[..., 1, 0], out[..., 1, 1], out[..., 1, 2] = (
        sy * cp,
        sy * sp * sr + cy * cr,
        sy * sp * cr - cy * sr,
    )
    out[..., 2, 0], out[..., 2, 1], out[..., 2, 2] = -sp, cp * sr, cp * cr
    return out


def matrix_to_quaternion(r: ArrayLike) -> Array:
    """The unit quaternion ``(qw, qx, qy, qz)`` of ``R`` with ``qw ≥ 0`` (one of ``±q``),
    by Shepperd's method (the largest of ``qw², qx², qy², qz²`` first, so no division by a
    small number)."""
    m = np.asarray(r, dtype=float)
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    squares = [1 + tr, 1 + 2 * m[0, 0] - tr, 1 + 2 * m[1, 1] - tr, 1 + 2 * m[2, 2] - tr]
    k = int(np.argmax(squares))
    big = math.sqrt(squares[k]) / 2
    if k == 0:
        q = [
            big,
            (m[2, 1] - m[1, 2]) / (4 * big),
            (m[0, 2] - m[2, 0]) / (4 * big),
            (m[1, 0] - m[0, 1]) / (4 * big),
        ]
    elif k == 1:
        q = [
            (m[2, 1] - m[1, 2]) / (4 * big),
            big,
            (m[0, 1] + m[1, 0]) / (4 * big),
            (m[0, 2] + m[2, 0]) / (4 * big),
        ]
    elif k == 2:
        q = [
            (m[0, 2] - m[2, 0]) / (4 * big),
            (m[0, 1] + m[1, 0]) / (4 * big),
            big,
            (m[1, 2] + m[2, 1]) / (4 * big),
        ]
    else:
        q = [
            (m[1, 0] - m[0, 1]) / (4 * big),
            (m[0, 2] + m[2, 0]) / (4 * big),
            (m[1, 2] + m[2, 1]) / (4 * big),
            big,
        ]
    out = np.array(q)
    return -out if out[0] < 0 else out


def quaternion_to_matrix(q: ArrayLike) -> Array:
    """The rotation of the quaternion ``(qw, qx, qy, qz)`` (normalised first); ``q`` and ``−q``
    give the same matrix."""
    w, x, y, z = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
        ]
    )


def quaternion_multiply(p: ArrayLike, q: ArrayLike) -> Array:
    """The Hamilton product ``p ⊗ q`` (the rotation of ``q`` first, then ``p``'s)."""
    pw, px, py, pz = np.asarray(p, dtype=float)
    qw, qx, qy, qz = np.asarray(q, dtype=float)
    return np.array(
        [
            pw * qw - px * qx - py * qy - pz * qz,
            pw * qx + px * qw + py * qz - pz * qy,
            pw * qy - px * qz + py * qw + pz * qx,
            pw * qz + px * qy - py * qx + pz * qw,
        ]
    )


# --- SE(3) --------------------------------------------------------------------------------------


def pose(r: ArrayLike, t: ArrayLike) -> Array:
    """The 4×4 (or ``(m, 4, 4)``) homogeneous matrices of rotations ``r`` and translations ``t``."""
    rot = np.asarray(r, dtype=float)
    out = np.zeros((*rot.shape[:-2], 4, 4))
    out[..., :3, :3] = rot
    out[..., :3, 3] = np.asarray(t, dtype=float)
    out[..., 3, 3] = 1.0
    return out


def inverse(x: ArrayLike) -> Array:
    """``T⁻¹ = [[Rᵀ, −Rᵀ t], [0, 1]]`` of one or a stack of poses."""
    m = np.asarray(x, dtype=float)
    rt = np.swapaxes(m[..., :3, :3], -1, -2)
    return pose(rt, -np.einsum("...ij,...j->...i", rt, m[..., :3, 3]))


def se3_exp(xi: ArrayLike) -> Array:
    """``Exp(ρ, φ) = [[Exp(φ), V(φ) ρ], [0, 1]]`` with ``V = J_l(φ) = I + ((1 − cos θ)/θ²) K +
    ((θ − sin θ)/θ³) K²``; ``(…, 6)`` → ``(…, 4, 4)``."""
    v = np.asarray(xi, dtype=float)
    rho, phi = v[..., :3], v[..., 3:]
    _, b, c = _coefficients(np.linalg.norm(phi, axis=-1))
    k = hat(phi)
    big_v = np.eye(3) + b[..., None, None] * k + c[..., None, None] * (k @ k)
    return pose(so3_exp(phi), np.einsum("...ij,...j->...i", big_v, rho))


def se3_log(x: ArrayLike) -> Array:
    """The tangent vector ``(ρ, φ)`` with ``Exp(ρ, φ) = T``: ``φ = Log R``, ``ρ = V(φ)⁻¹ t``."""
    m = np.asarray(x, dtype=float)
    phi = so3_log(m[..., :3, :3])
    _, b, c = _coefficients(np.linalg.norm(phi, axis=-1))
    k = hat(phi)
    big_v = np.eye(3) + b[..., None, None] * k + c[..., None, None] * (k @ k)
    rho = np.linalg.solve(big_v, m[..., :3, 3][..., None])[..., 0]
    return np.concatenate([rho, phi], axis=-1)


def adjoint(x: ArrayLike) -> Array:
    """``Ad(T) = [[R, [t]× R], [0, R]]`` (6×6, tangent order ``(ρ, φ)``):
    ``T Exp(ξ) T⁻¹ = Exp(Ad(T) ξ)``."""
    m = np.asarray(x, dtype=float)
    r, t = m[..., :3, :3], m[..., :3, 3]
    out = np.zeros((*m.shape[:-2], 6, 6))
    out[..., :3, :3] = r
    out[..., :3, 3:] = hat(t) @ r
    out[..., 3:, 3:] = r
    return out


def between(xi: ArrayLike, xj: ArrayLike) -> Array:
    """``X_i⁻¹ X_j``: pose ``j`` seen from pose ``i``."""
    out: Array = inverse(xi) @ np.asarray(xj, dtype=float)
    return out


def between_jacobians(xi: ArrayLike, xj: ArrayLike) -> tuple[Array, Array]:
    """Right-perturbation Jacobians of ``Y = X_i⁻¹ X_j``: with ``X ⊞ δ = X Exp(δ)``,
    ``Y(X_i ⊞ δ_i, X_j ⊞ δ_j) ≈ Y ⊞ (J_i δ_i + J_j δ_j)``, ``J_i = −Ad(Y⁻¹)``, ``J_j = I``."""
    y = between(xi, xj)
    return -adjoint(inverse(y)), np.eye(6)


# --- the 3-D pose graph -------------------------------------------------------------------------


@dataclass(frozen=True)
class Graph3:
    """Poses (``(n, 4, 4)``) and edges as arrays: ``i``, ``j`` (``(m,)``), measurements ``z``
    (``(m, 4, 4)``) and informations ``omega`` (``(m, 6, 6)``, order ``x y z φx φy φz``)."""

    poses: Array
    i: NDArray[np.intp]
    j: NDArray[np.intp]
    z: Array
    omega: Array

    def subgraph(self, first: int, count: int) -> Graph3:
        """Poses ``first … first+count−1`` and every edge among them, renumbered from 0."""
        keep = (self.i >= first) & (self.i < first + count)
        keep &= (self.j >= first) & (self.j < first + count)
        return Graph3(
            self.poses[first : first + count].copy(),
            self.i[keep] - first,
            self.j[keep] - first,
            self.z[keep],
            self.omega[keep],
        )


def information_from_sqrt_upper(values: Sequence[float] | Array) -> Array:
    """``Ω = Sᵀ S`` from the 21 numbers of the upper-triangular square-root information ``S``
    (row by row); ``(…, 21)`` → ``(…, 6, 6)``."""
    v = np.asarray(values, dtype=float)
    s = np.zeros((*v.shape[:-1], 6, 6))
    rows, cols = np.triu_indices(6)
    s[..., rows, cols] = v
    out: Array = np.swapaxes(s, -1, -2) @ s
    return out


def parse_edge3(text: str) -> Graph3:
    """Read ``EDGE3 i j x y z roll pitch yaw s11 s12 … s66`` lines (other lines are skipped).

    The initial guess composes the odometry edges ``(k, k+1)`` from pose 0 at the origin;
    poses are numbered 0 … n−1 with ``n − 1`` the largest id.
    """
    rows = [line.split() for line in text.splitlines()]
    rows = [f for f in rows if f and f[0] == "EDGE3"]
    ij = np.array([[int(f[1]), int(f[2])] for f in rows], dtype=np.intp).reshape(-1, 2)
    values = np.array([[float(v) for v in f[3:30]] for f in rows], dtype=float).reshape(-1, 27)
    z = pose(rpy_matrix(values[:, 3], values[:, 4], values[:, 5]), values[:, :3])
    omega = information_from_sqrt_upper(values[:, 6:])
    n = int(ij.max()) + 1 if len(ij) else 0
    step = {(int(a), int(b)): k for k, (a, b) in enumerate(ij) if b == a + 1}
    poses = np.empty((n, 4, 4))
    if n:
        poses[0] = np.eye(4)
    for k in range(1, n):
        poses[k] = poses[k - 1] @ z[step[(k - 1, k)]]
    return Graph3(poses, ij[:, 0].copy(), ij[:, 1].copy(), z, omega)


def edge_errors(x: Array, graph: Graph3) -> tuple[Array, Array, Array]:
    """All edges at once: errors ``e = (t_E, Log R_E)`` (``(m, 6)``) of ``E = Z⁻¹ X_i⁻¹ X_j`` and
    their Jacobians ``A = ∂e/∂δ_i``, ``B = ∂e/∂δ_j`` (``(m, 6, 6)``) for ``X ⊞ δ = X Exp(δ)``.

    ``B = D = diag(R_E, J_r⁻¹(Log R_E))`` (the derivative of ``e`` under ``E Exp(ξ)``) and
    ``A = −D Ad(Y⁻¹)`` with ``Y = X_i⁻¹ X_j``, because ``X_i Exp(δ)`` moves ``Y`` to
    ``Y Exp(−Ad(Y⁻¹) δ)``.
    """
    y = between(x[graph.i], x[graph.j])
    big_e = inverse(graph.z) @ y
    phi = so3_log(big_e[:, :3, :3])
    e = np.concatenate([big_e[:, :3, 3], phi], axis=1)
    d = np.zeros((len(e), 6, 6))
    d[:, :3, :3] = big_e[:, :3, :3]
    d[:, 3:, 3:] = right_jacobian_inverse(phi)
    a = -d @ adjoint(inverse(y))
    return e, a, d


ErrorModel = Callable[[Array, "Graph3"], tuple[Array, Array, Array]]
"""Errors and Jacobians of all edges at the poses (:func:`edge_errors` and its mistaken twins)."""


def chi2(x: Array, graph: Graph3, model: ErrorModel | None = None) -> float:
    """``Σ eᵀ Ω e`` over all edges (dimensionless); ``model`` defaults to :func:`edge_errors`."""
    e, _, _ = (model or edge_errors)(x, graph)
    return float(np.einsum("ki,kij,kj->", e, graph.omega, e))


ORDERED_POSES = 500
"""From this many poses on, :func:`gauss_newton` orders the unknowns itself (see
:func:`elimination_order`); below it, computing the order costs more than it saves."""


def elimination_order(n: int, graph: Graph3, anchor: int = 0) -> NDArray[np.intp]:
    """The order in which a Gauss-Newton step eliminates the unknowns of ``graph``'s ``n``
    poses (``anchor`` held fixed): pose by pose in the greedy minimum-degree order of the
    orderings chapter, each pose's six entries together; indices into the system without the
    anchor's. On sphere2500 a step's solve takes 0.19 s in this order and 0.55 s in the
    sparse solver's own column order (COLAMD), whose fill-in a pose graph's symmetry defeats."""
    from slamcourse.slam.orderings import min_degree_order

    edges = zip(graph.i.tolist(), graph.j.tolist(), strict=True)
    poses = [k for k in min_degree_order(n, edges) if k != anchor]
    reduced = np.array([k - (k > anchor) for k in poses], dtype=np.intp)
    out: NDArray[np.intp] = (6 * reduced[:, None] + np.arange(6)).ravel()
    return out


def _solve(h: Any, rhs: Array, order: NDArray[np.intp] | None) -> Array:
    """``h⁻¹ rhs`` for the symmetric sparse ``h``: by the sparse solver's own ordering, or
    with ``order`` (:func:`elimination_order`) as the LU factorisation's, its pivots kept on
    the diagonal where they are not tiny (symmetric mode: the order's fill-in is kept)."""
    from scipy.sparse.linalg import splu, spsolve  # type: ignore[import-untyped]

    if order is None:
        out: Array = spsolve(h, rhs)
        return out
    permuted = h.tocsr()[order][:, order].tocsc()
    lu = splu(
        permuted,
        permc_spec="NATURAL",
        diag_pivot_thresh=0.01,
        options={"SymmetricMode": True},
    )
    out = np.empty_like(rhs)
    out[order] = lu.solve(rhs[order])
    return out


def gauss_newton_step(
    x: Array,
    graph: Graph3,
    anchor: int = 0,
    model: ErrorModel | None = None,
    order: NDArray[np.intp] | None = None,
) -> Array:
    """One undamped Gauss-Newton step with pose ``anchor`` held fixed, sparse (scipy): build
    ``H = Σ Jᵀ Ω J`` and ``b = Σ Jᵀ Ω e``, solve ``H δ = −b`` (in ``order``, if given:
    :func:`elimination_order`), apply ``X_k ← X_k Exp(δ_k)``."""
    from scipy.sparse import coo_matrix  # type: ignore[import-untyped]

    n = len(x)
    e, a, b = (model or edge_errors)(x, graph)
    at_om = np.swapaxes(a, 1, 2) @ graph.omega
    bt_om = np.swapaxes(b, 1, 2) @ graph.omega
    g = np.zeros(6 * n)
    k6 = np.arange(6)
    np.add.at(g, 6 * graph.i[:, None] + k6, np.einsum("kij,kj->ki", at_om, e))
    np.add.at(g, 6 * graph.j[:, None] + k6, np.einsum("kij,kj->ki", bt_om, e))
    rows, cols, values = [], [], []
    blocks = (
        (graph.i, graph.i, at_om @ a),
        (graph.i, graph.j, at_om @ b),
        (graph.j, graph.i, bt_om @ a),
        (graph.j, graph.j, bt_om @ b),
    )
    for p, q, block in blocks:
        rows.append(np.broadcast_to(6 * p[:, None, None] + k6[None, :, None], block.shape).ravel())
        cols.append(np.broadcast_to(6 * q[:, None, None] + k6[None, None, :], block.shape).ravel())
        values.append(block.ravel())
    h = coo_matrix(
        (np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(6 * n, 6 * n)
    ).tocsc()
    keep = np.ones(6 * n, dtype=bool)
    keep[6 * anchor : 6 * anchor + 6] = False
    delta = np.zeros(6 * n)
    delta[keep] = _solve(h[keep][:, keep], -g[keep], order)
    out: Array = x @ se3_exp(delta.reshape(n, 6))
    return out


def gauss_newton(
    x: ArrayLike, graph: Graph3, iterations: int, model: ErrorModel | None = None
) -> tuple[Array, list[float]]:
    """``iterations`` Gauss-Newton steps from ``x``; the poses and χ² before each step and after.
    A graph of :data:`ORDERED_POSES` poses or more is solved in :func:`elimination_order`."""
    poses = np.array(x, dtype=float)
    history = [chi2(poses, graph, model)]
    order = elimination_order(len(poses), graph) if len(poses) >= ORDERED_POSES else None
    for _ in range(iterations):
        poses = gauss_newton_step(poses, graph, model=model, order=order)
        history.append(chi2(poses, graph, model))
    return poses, history


def relative_to_first(x: ArrayLike) -> Array:
    """Every pose seen from pose 0, ``X_0⁻¹ X_k`` (``(n, 4, 4)``): a gauge-free summary."""
    m = np.asarray(x, dtype=float)
    out: Array = inverse(m[0]) @ m
    return out


def positions_from_first(x: ArrayLike) -> Array:
    """The positions of ``X_0⁻¹ X_k`` (``(n, 3)``): where each pose is, seen from pose 0."""
    return relative_to_first(x)[:, :3, 3]


def align(points: ArrayLike, target: ArrayLike) -> Array:
    """``points`` (``(n, 3)``) moved by the rigid motion that best fits them to ``target`` in the
    least-squares sense (Kabsch/Umeyama without scale)."""
    p, q = np.asarray(points, dtype=float), np.asarray(target, dtype=float)
    pc, qc = p.mean(axis=0), q.mean(axis=0)
    u, _, vt = np.linalg.svd((q - qc).T @ (p - pc))
    d = np.diag([1.0, 1.0, float(np.sign(np.linalg.det(u @ vt)))])
    r = u @ d @ vt
    out: Array = (p - pc) @ r.T + qc
    return out


def ate_rmse(points: ArrayLike, target: ArrayLike) -> float:
    """Absolute trajectory error: the RMS distance after the best rigid alignment (metres)."""
    moved = align(points, target)
    return float(np.sqrt(np.mean(np.sum((moved - np.asarray(target)) ** 2, axis=1))))


def to_edge3(graph: Graph3, sqrt_information: Array | None = None) -> str:
    """A graph's edges as ``EDGE3`` text (roll, pitch, yaw of ``Rz Ry Rx``); the upper triangle
    of ``S`` is taken from ``sqrt_information`` (``(m, 6, 6)``, upper triangular) or, without
    it, from the Cholesky factor of ``Ω``."""
    if sqrt_information is None:
        s = np.swapaxes(np.linalg.cholesky(graph.omega), -1, -2)
    else:
        s = np.asarray(sqrt_information, dtype=float)
    rows, cols = np.triu_indices(6)
    lines = []
    for k in range(len(graph.i)):
        r, t = graph.z[k, :3, :3], graph.z[k, :3, 3]
        roll, pitch, yaw = rpy_angles(r)
        numbers = [*t, roll, pitch, yaw, *s[k][rows, cols]]
        values = " ".join(repr(float(v)) for v in numbers)
        lines.append(f"EDGE3 {int(graph.i[k])} {int(graph.j[k])} {values}")
    return "\n".join(lines) + "\n"


def rpy_angles(r: ArrayLike) -> tuple[float, float, float]:
    """``(roll, pitch, yaw)`` with ``R = Rz(yaw) Ry(pitch) Rx(roll)``, pitch in [−π/2, π/2]."""
    m = np.asarray(r, dtype=float)
    pitch = math.asin(max(-1.0, min(1.0, -float(m[2, 0]))))
    roll = math.atan2(float(m[2, 1]), float(m[2, 2]))
    yaw = math.atan2(float(m[1, 0]), float(m[0, 0]))
    return roll, pitch, yaw


def simulate(
    seed: int, n: int, loops: int, *, turn: float = 1.0, correlated: bool = False
) -> tuple[Array, str]:
    """A synthetic 3-D pose graph as ``EDGE3`` text, and its true poses (``(n, 4, 4)``).

    A random walk of ``n`` poses (steps of 0.5–1.5 m mostly forward, rotation vectors of up to
    ``turn`` radians, so roll and pitch are large too), its odometry edges ``(k, k+1)`` and
    ``loops`` loop closures between random pairs, each measured with noise of a few centimetres
    and about a degree. Each edge gets its own upper-triangular square-root information ``S``
    (diagonal unless ``correlated``).
    """
    rng = np.random.default_rng(seed)
    steps = np.zeros((n - 1, 6))
    steps[:, 0] = rng.uniform(0.5, 1.5, n - 1)
    steps[:, 1:3] = rng.uniform(-0.3, 0.3, (n - 1, 2))
    axes = rng.normal(size=(n - 1, 3))
    axes /= np.linalg.norm(axes, axis=1, keepdims=True)
    steps[:, 3:] = axes * rng.uniform(0, turn, (n - 1, 1))
    truth = [np.eye(4)]
    for k in range(n - 1):
        truth.append(truth[-1] @ pose(so3_exp(steps[k, 3:]), steps[k, :3]))
    x = np.array(truth)
    pairs = [(k, k + 1) for k in range(n - 1)]
    for _ in range(loops if n > 2 else 0):
        a, b = (int(v) for v in rng.choice(n, size=2, replace=False))
        pairs.append((a, b))
    i = np.array([p[0] for p in pairs], dtype=np.intp)
    j = np.array([p[1] for p in pairs], dtype=np.intp)
    m = len(pairs)
    sigma = np.concatenate(
        [rng.uniform(0.02, 0.1, (m, 3)), rng.uniform(0.005, 0.03, (m, 3))], axis=1
    )
    s = np.zeros((m, 6, 6))
    s[:, np.arange(6), np.arange(6)] = 1 / sigma
    if correlated:
        upper = np.triu(rng.uniform(-0.3, 0.3, (m, 6, 6)), 1)
        s += upper * (1 / sigma)[:, :, None]
    noise = rng.normal(size=(m, 6)) * sigma
    z = between(x[i], x[j]) @ se3_exp(noise)
    omega = np.swapaxes(s, -1, -2) @ s
    graph = Graph3(x, i, j, z, omega)
    return x, to_edge3(graph, np.round(s, 3))


@lru_cache(maxsize=4)
def optimise_text(text: str, iterations: int) -> tuple[Array, tuple[float, ...]]:
    """EDGE3 text optimised from its composed odometry: the poses after ``iterations``
    Gauss-Newton steps and χ² before each step and after (cached: sphere2500's ten steps are
    shared by the chapter's reference, its figure and its tests)."""
    graph = parse_edge3(text)
    x, history = gauss_newton(graph.poses, graph, iterations)
    x.setflags(write=False)
    return x, tuple(history)
