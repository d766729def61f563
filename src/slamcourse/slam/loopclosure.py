"""Loop closures: proposing them from the graph's own uncertainty, and testing them against it.

Conventions are those of :mod:`slamcourse.slam.posegraph` (g2o's): poses ``x = (x, y, θ)`` in
metres and radians, an edge ``(i, j, z, Ω)`` measures pose ``j`` from pose ``i`` with error
``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)`` and ``Ω`` the information of that error.

- The **marginal covariance** of the optimised poses is ``Σ = H⁻¹`` (``H = Σ Jᵀ Ω J`` with the
  anchor's rows and columns removed; the anchor's own blocks are zero). ``Σ_ij`` is the 3×3
  block of rows of pose ``i`` and columns of pose ``j``, so ``Σ_ji = Σ_ijᵀ``.
- The **relative pose** ``r = x_i⁻¹ ⊕ x_j`` (pose ``j`` seen from pose ``i``) has, to first
  order, the covariance ``J_i Σ_ii J_iᵀ + J_i Σ_ij J_jᵀ + J_j Σ_ji J_iᵀ + J_j Σ_jj J_jᵀ`` with
  ``J_i``, ``J_j`` its Jacobians (those of the pose-graph error with ``z = 0``).
- A candidate closure ``(i, j, z, Ω)`` is tested by its **normalised innovation squared**
  ``NIS = eᵀ S⁻¹ e`` with ``S = [A B] Σ_{ij} [A B]ᵀ + Ω⁻¹`` (``A``, ``B`` the edge's Jacobians,
  ``Σ_{ij}`` the 6×6 joint covariance of the two poses); a correct closure gives
  ``NIS ~ χ²₃``.
- The **candidate search** for the current pose ``k`` gates the squared Mahalanobis distance of
  the relative position ``r_xy`` (pose ``k`` seen from pose ``i``) under the top-left 2×2 block
  of its covariance: "could the robot now stand where it stood at pose ``i``?"
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import posegraph as pg
from slamcourse.slam.se2 import between

Matrix = NDArray[np.float64]


def relative_jacobians(xi: Sequence[float], xj: Sequence[float]) -> tuple[Matrix, Matrix]:
    """``J_i = ∂r/∂x_i`` and ``J_j = ∂r/∂x_j`` (3×3 each) of ``r = x_i⁻¹ ⊕ x_j``.

    ``r_xy = R_iᵀ (t_j − t_i)`` and ``r_θ = θ_j − θ_i``: ``J_i = [[−R_iᵀ, (dR_iᵀ/dθ)(t_j − t_i)],
    [0, 0, −1]]`` and ``J_j = [[R_iᵀ, 0], [0, 0, 1]]``.
    """
    return pg.edge_jacobians(xi, xj, (0.0, 0.0, 0.0))


def joint(sii: ArrayLike, sij: ArrayLike, sjj: ArrayLike) -> Matrix:
    """The 6×6 joint covariance ``[[Σ_ii, Σ_ij], [Σ_ijᵀ, Σ_jj]]`` of two poses."""
    a, c, b = (np.asarray(m, dtype=float) for m in (sii, sij, sjj))
    return np.block([[a, c], [c.T, b]])


def relative_pose_covariance(
    xi: Sequence[float], xj: Sequence[float], sii: ArrayLike, sij: ArrayLike, sjj: ArrayLike
) -> Matrix:
    """First-order covariance (3×3) of ``x_i⁻¹ ⊕ x_j`` from the poses' marginal blocks."""
    ji, jj = relative_jacobians(xi, xj)
    j = np.hstack([ji, jj])
    out = j @ joint(sii, sij, sjj) @ j.T
    return np.asarray((out + out.T) / 2, dtype=float)


def innovation_covariance(
    xi: Sequence[float],
    xj: Sequence[float],
    sii: ArrayLike,
    sij: ArrayLike,
    sjj: ArrayLike,
    z: Sequence[float],
    information: ArrayLike,
) -> Matrix:
    """``S = [A B] Σ [A B]ᵀ + Ω⁻¹`` (3×3): the covariance of a new edge's error ``e``."""
    a, b = pg.edge_jacobians(xi, xj, z)
    j = np.hstack([a, b])
    s = j @ joint(sii, sij, sjj) @ j.T + np.linalg.inv(np.asarray(information, dtype=float))
    return np.asarray((s + s.T) / 2, dtype=float)


def closure_nis(
    xi: Sequence[float],
    xj: Sequence[float],
    sii: ArrayLike,
    sij: ArrayLike,
    sjj: ArrayLike,
    z: Sequence[float],
    information: ArrayLike,
) -> float:
    """``eᵀ S⁻¹ e`` of a candidate edge ``(i, j, z, Ω)`` against the graph's estimate."""
    e = pg.edge_error(xi, xj, z)
    s = innovation_covariance(xi, xj, sii, sij, sjj, z, information)
    return float(e @ np.linalg.solve(s, e))


def chi2_gate(dof: int, confidence: float) -> float:
    """The ``confidence`` quantile of ``χ²`` with ``dof`` degrees of freedom."""
    from scipy.stats import chi2  # type: ignore[import-untyped]

    return float(chi2.ppf(confidence, dof))


def position_d2(
    xi: Sequence[float], xk: Sequence[float], sii: ArrayLike, sik: ArrayLike, skk: ArrayLike
) -> float:
    """Squared Mahalanobis distance of ``r_xy`` (pose ``k`` seen from pose ``i``) from 0."""
    r = between(xi, xk)
    c = relative_pose_covariance(xi, xk, sii, sik, skk)[:2, :2]
    t = np.array(r[:2])
    return float(t @ np.linalg.solve(c, t))


def relative_positions(
    poses: ArrayLike, marginals: ArrayLike, cross: ArrayLike, gap: int
) -> tuple[NDArray[np.int64], Matrix, Matrix]:
    """For every pose ``i ≤ k − gap`` (``k`` the last pose): the indices, ``r_xy`` of pose ``k``
    seen from pose ``i`` (m×2) and its covariance ``(Σ_r)_xy`` (m×2×2).

    ``marginals[i] = Σ_ii`` and ``cross[i] = Σ_ik`` (n×3×3 each). All poses at once: the
    2×6 Jacobians of ``r_xy`` stacked, ``(Σ_r)_xy = J P Jᵀ`` by ``einsum``; equal to
    :func:`relative_pose_covariance` pose by pose (tested)."""
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    idx = np.arange(0, max(k - int(gap) + 1, 0), dtype=np.int64)
    cs, sn = np.cos(x[idx, 2]), np.sin(x[idx, 2])
    dx, dy = x[k, 0] - x[idx, 0], x[k, 1] - x[idx, 1]
    rx, ry = cs * dx + sn * dy, -sn * dx + cs * dy
    zero = np.zeros(len(idx))
    # rows ∂r_x and ∂r_y by (x_i, y_i, θ_i, x_k, y_k, θ_k)
    jac = np.stack(
        [
            np.stack([-cs, -sn, ry, cs, sn, zero], axis=1),
            np.stack([sn, -cs, -rx, -sn, cs, zero], axis=1),
        ],
        axis=1,
    ).reshape(len(idx), 2, 6)
    joint = np.empty((len(idx), 6, 6))
    joint[:, :3, :3] = m[idx]
    joint[:, :3, 3:] = c[idx]
    joint[:, 3:, :3] = np.transpose(c[idx], (0, 2, 1))
    joint[:, 3:, 3:] = m[k]
    s = np.einsum("nab,nbc,ndc->nad", jac, joint, jac)
    return idx, np.stack([rx, ry], axis=1).reshape(len(idx), 2), (s + s.transpose(0, 2, 1)) / 2


def candidate_distances(
    poses: ArrayLike, marginals: ArrayLike, cross: ArrayLike, gap: int
) -> dict[int, float]:
    """``{i: d²_i}`` for every pose ``i ≤ k − gap``, ``k`` the last pose (the current one);
    ``d²_i = r_xyᵀ (Σ_r)_xy⁻¹ r_xy`` (see :func:`relative_positions`)."""
    idx, r, s = relative_positions(poses, marginals, cross, gap)
    if len(idx) == 0:
        return {}
    d2 = np.einsum("na,na->n", r, np.linalg.solve(s, r[:, :, None])[:, :, 0])
    return {int(i): float(v) for i, v in zip(idx, d2, strict=True)}


def loop_candidates(
    poses: ArrayLike, marginals: ArrayLike, cross: ArrayLike, gap: int, gate: float
) -> list[int]:
    """The poses ``i ≤ k − gap`` whose ``d²_i ≤ gate``, in increasing order."""
    return [i for i, d2 in candidate_distances(poses, marginals, cross, gap).items() if d2 <= gate]


# --- covariances of a pose graph ----------------------------------------------------------------


def covariance(poses: ArrayLike, edges: Sequence[pg.Edge], anchor: int = 0) -> Matrix:
    """The full marginal covariance ``H⁻¹`` (3n×3n, dense) at ``poses``, pose ``anchor`` fixed
    (its rows and columns are zero)."""
    x = np.asarray(poses, dtype=float)
    h, _ = pg.linear_system(x, edges)
    keep = np.ones(len(h), dtype=bool)
    keep[3 * anchor : 3 * anchor + 3] = False
    out = np.zeros_like(h)
    out[np.ix_(keep, keep)] = np.linalg.inv(h[np.ix_(keep, keep)])
    return (out + out.T) / 2


def joint_covariance(
    poses: ArrayLike, edges: Sequence[pg.Edge], i: int, j: int, anchor: int = 0
) -> Matrix:
    """The 6×6 joint covariance of poses ``i`` and ``j`` (blocks of ``H⁻¹``, pose ``anchor``
    fixed) without forming ``H⁻¹``: one sparse LU factorisation of ``H`` and six solves for
    the block columns of the two poses, as a real system recovers them."""
    from scipy.sparse import coo_matrix  # type: ignore[import-untyped]
    from scipy.sparse.linalg import splu  # type: ignore[import-untyped]

    x = np.asarray(poses, dtype=float)
    n3 = 3 * len(x)
    _, a, b, om = pg.stacked_errors(x, edges)
    ii = np.array([e.i for e in edges])
    jj = np.array([e.j for e in edges])
    rows, cols, vals = [], [], []
    off = np.arange(3)
    for p, q, left, right in ((ii, ii, a, a), (ii, jj, a, b), (jj, ii, b, a), (jj, jj, b, b)):
        blocks = np.einsum("kji,kjl,klm->kim", left, om, right)
        rows.append((3 * p[:, None, None] + off[None, :, None] + 0 * off).ravel())
        cols.append((3 * q[:, None, None] + 0 * off[:, None] + off[None, None, :]).ravel())
        vals.append(blocks.ravel())
    h = coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n3, n3)
    ).tocsc()
    keep = np.ones(n3, dtype=bool)
    keep[3 * anchor : 3 * anchor + 3] = False
    index = np.cumsum(keep) - 1
    lu = splu(h[keep][:, keep])
    wanted = [*range(3 * i, 3 * i + 3), *range(3 * j, 3 * j + 3)]
    out = np.zeros((6, 6))
    for c, col in enumerate(wanted):
        if not keep[col]:
            continue
        unit = np.zeros(int(keep.sum()))
        unit[index[col]] = 1.0
        full = np.zeros(n3)
        full[keep] = lu.solve(unit)
        out[:, c] = full[wanted]
    return (out + out.T) / 2


def block(cov: ArrayLike, i: int, j: int) -> Matrix:
    """``Σ_ij``: rows of pose ``i``, columns of pose ``j`` (3×3)."""
    c = np.asarray(cov, dtype=float)
    return c[3 * i : 3 * i + 3, 3 * j : 3 * j + 3].copy()


@dataclass(frozen=True)
class Snapshot:
    """The graph a robot holds at one moment: poses ``first … last`` of a larger graph (renumbered
    from 0), every edge among them but the ``withheld`` ones, optimised, and its covariance
    (the first pose fixed)."""

    first: int
    poses: Matrix
    edges: tuple[pg.Edge, ...]
    cov: Matrix

    def local(self, pose: int) -> int:
        """The snapshot's index of the larger graph's pose ``pose``."""
        return pose - self.first


def snapshot(
    graph: pg.PoseGraph,
    first: int,
    last: int,
    withheld: Iterable[tuple[int, int]] = (),
    iterations: int = 10,
) -> Snapshot:
    """The optimised graph of poses ``first … last`` without the ``withheld`` edges (given by
    their ids in ``graph``)."""
    skip = set(withheld)
    keep = range(first, last + 1)
    edges = tuple(
        pg.Edge(e.i - first, e.j - first, e.z, e.information)
        for e in graph.edges
        if e.i in keep and e.j in keep and (e.i, e.j) not in skip
    )
    x, _ = pg.gauss_newton(graph.poses[first : last + 1], edges, iterations)
    return Snapshot(first, x, edges, covariance(x, edges))


def odometry_covariances(poses: ArrayLike, edges: Sequence[pg.Edge]) -> Matrix:
    """Marginal covariances (n×3×3) of a chain of odometry edges ``k → k+1`` with pose 0 fixed,
    propagated step by step: ``Σ_{k+1} = F Σ_k Fᵀ + G Ω⁻¹ Gᵀ`` with ``F`` the Jacobian of
    ``x_k ⊕ z`` by ``x_k`` and ``G`` the rotation by ``θ_k + z_θ`` (the error of an edge is the
    noise ``δ`` in ``x_{k+1} = x_k ⊕ z ⊕ δ``). Equal to the diagonal blocks of the chain's
    ``H⁻¹``; ``poses`` only supply the headings, taken as those of dead reckoning."""
    x = np.asarray(poses, dtype=float)
    out = np.zeros((len(x), 3, 3))
    for k, e in enumerate(edges):
        theta = float(x[k, 2])
        c, s = math.cos(theta), math.sin(theta)
        dx, dy = e.z[0], e.z[1]
        f = np.array([[1.0, 0.0, -s * dx - c * dy], [0.0, 1.0, c * dx - s * dy], [0.0, 0.0, 1.0]])
        cg, sg = math.cos(theta + e.z[2]), math.sin(theta + e.z[2])
        g = np.array([[cg, -sg, 0.0], [sg, cg, 0.0], [0.0, 0.0, 1.0]])
        out[k + 1] = f @ out[k] @ f.T + g @ np.linalg.inv(e.information) @ g.T
    return out


def ellipse(cov2: ArrayLike, scale: float) -> tuple[float, float, float]:
    """Semi-axes (``scale`` standard deviations, metres) and the angle (rad) of the major axis of
    a 2×2 covariance's ellipse."""
    w, v = np.linalg.eigh(np.asarray(cov2, dtype=float))
    w = np.clip(w, 0.0, None)
    return (
        float(scale * math.sqrt(w[1])),
        float(scale * math.sqrt(w[0])),
        float(math.atan2(v[1, 1], v[0, 1])),
    )
