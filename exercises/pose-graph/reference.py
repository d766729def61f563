"""Reference answers for chapter ``pose-graph``: edge errors, their Jacobians, Gauss-Newton.

Conventions (g2o's): an edge ``(i, j, z, Ω)`` measures pose ``j`` from pose ``i``; its error is
``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)`` with the angle wrapped into (−π, π]; ``χ² = Σ eᵀ Ω e``;
``A = ∂e/∂x_i``, ``B = ∂e/∂x_j``. The mathematics lives in :mod:`slamcourse.slam.posegraph`.
Functions whose name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import posegraph as pg
from slamcourse.slam import se2

Pose = Sequence[float]
Matrix = NDArray[np.float64]


# --- numeric exercises ------------------------------------------------------------------------


def error_value(
    xi: float, yi: float, ti: float, xj: float, yj: float, tj: float, zx: float, zy: float, zt: float
) -> list[float]:
    return pg.edge_error((xi, yi, ti), (xj, yj, tj), (zx, zy, zt)).tolist()  # type: ignore[no-any-return]


def mistake_error_subtracted(
    xi: float, yi: float, ti: float, xj: float, yj: float, tj: float, zx: float, zy: float, zt: float
) -> list[float]:
    """``(x_i⁻¹ ⊕ x_j) − z`` component by component: right only when ``z``'s angle is 0."""
    rel = se2.between((xi, yi, ti), (xj, yj, tj))
    return [rel[0] - zx, rel[1] - zy, se2.wrap_angle(rel[2] - zt)]


def mistake_error_world_frame(
    xi: float, yi: float, ti: float, xj: float, yj: float, tj: float, zx: float, zy: float, zt: float
) -> list[float]:
    """``(x_j − x_i) − z`` in world coordinates."""
    return [xj - xi - zx, yj - yi - zy, se2.wrap_angle(tj - ti - zt)]


def edge_chi2(ex: float, ey: float, et: float, wxy: float, wt: float) -> float:
    e = np.array([ex, ey, et])
    return float(e @ np.diag([wxy, wxy, wt]) @ e)


def mistake_chi2_covariance(ex: float, ey: float, et: float, wxy: float, wt: float) -> float:
    """``eᵀ Ω⁻¹ e``: the information matrix read as a covariance."""
    return (ex**2 + ey**2) / wxy + et**2 / wt


def mistake_chi2_half(ex: float, ey: float, et: float, wxy: float, wt: float) -> float:
    """``½ eᵀ Ω e``: GTSAM's "error", half of χ²."""
    return edge_chi2(ex, ey, et, wxy, wt) / 2


def hessian_rank(n: int) -> int:
    """Rank of ``H`` for a connected graph of ``n`` poses and no anchor: ``3n − 3``."""
    rng = np.random.default_rng(n)
    poses = rng.uniform(-5, 5, size=(n, 3))
    edges = [pg.Edge(k, k + 1, (1.0, 0.0, 0.1), np.eye(3)) for k in range(n - 1)]
    edges.append(pg.Edge(0, n - 1, (0.5, 0.5, 0.2), np.eye(3)))
    h, _ = pg.linear_system(poses, edges)
    return int(np.linalg.matrix_rank(h))


def mistake_rank_full(n: int) -> int:
    return 3 * n


def mistake_rank_one_free(n: int) -> int:
    return 3 * n - 1


def mistake_rank_translation_only(n: int) -> int:
    return 3 * n - 2


# --- code: shared strategies ------------------------------------------------------------------


def _pose() -> Any:
    from hypothesis import strategies as st

    coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
    angle = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    return st.tuples(coord, coord, angle)


def _measurement() -> Any:
    from hypothesis import strategies as st

    coord = st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False)
    angle = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    return st.tuples(coord, coord, angle)


def edge_inputs() -> Any:
    """Two poses (metres in [−20, 20], radians in [−π, π]) and a measurement (metres in [−5, 5])."""
    from hypothesis import strategies as st

    return st.fixed_dictionaries({"xi": _pose(), "xj": _pose(), "z": _measurement()})


# --- code: edge_error -------------------------------------------------------------------------


def edge_error(xi: Pose, xj: Pose, z: Pose) -> list[float]:
    return pg.edge_error(xi, xj, z).tolist()  # type: ignore[no-any-return]


def mistake_edge_subtracted(xi: Pose, xj: Pose, z: Pose) -> list[float]:
    return mistake_error_subtracted(*xi, *xj, *z)


def mistake_edge_world_frame(xi: Pose, xj: Pose, z: Pose) -> list[float]:
    return mistake_error_world_frame(*xi, *xj, *z)


def mistake_edge_other_convention(xi: Pose, xj: Pose, z: Pose) -> list[float]:
    """``(x_i⁻¹ ⊕ x_j)⁻¹ ⊕ z``, the inverse of the g2o error (python-graphslam's convention)."""
    return list(se2.between(se2.between(xi, xj), z))


def mistake_edge_measurement_on_right(xi: Pose, xj: Pose, z: Pose) -> list[float]:
    """``(x_i⁻¹ ⊕ x_j) ⊕ z⁻¹``: ``z⁻¹`` composed on the wrong side."""
    return list(se2.compose(se2.between(xi, xj), se2.inverse(z)))


# --- code: edge_jacobians ---------------------------------------------------------------------


def edge_jacobians(xi: Pose, xj: Pose, z: Pose) -> Matrix:
    """``[A | B]``, 3×6."""
    a, b = pg.edge_jacobians(xi, xj, z)
    return np.hstack([a, b])


def mistake_jacobians_without_measurement(xi: Pose, xj: Pose, z: Pose) -> Matrix:
    """The Jacobians of ``x_i⁻¹ ⊕ x_j``: the rotation ``R_zᵀ`` left out."""
    return edge_jacobians(xi, xj, (0.0, 0.0, 0.0))


def mistake_jacobians_heading_column_sign(xi: Pose, xj: Pose, z: Pose) -> Matrix:
    """``∂e_xy/∂θ_i`` with the wrong sign."""
    j = edge_jacobians(xi, xj, z)
    j[:2, 2] *= -1
    return j


def mistake_jacobians_swapped(xi: Pose, xj: Pose, z: Pose) -> Matrix:
    """``[B | A]``: the two blocks in the wrong order."""
    j = edge_jacobians(xi, xj, z)
    return np.hstack([j[:, 3:], j[:, :3]])


def mistake_jacobians_b_is_minus_a(xi: Pose, xj: Pose, z: Pose) -> Matrix:
    """``B = −A``, as for a difference ``x_j − x_i``."""
    j = edge_jacobians(xi, xj, z)
    return np.hstack([j[:, :3], -j[:, :3]])


# --- code: gauss_newton -----------------------------------------------------------------------


def _plain_edges(edges: Sequence[pg.Edge]) -> list[list[Any]]:
    return [[e.i, e.j, list(e.z), e.information.tolist()] for e in edges]


def _edges(raw: Sequence[Sequence[Any]]) -> list[pg.Edge]:
    return [
        pg.Edge(int(i), int(j), tuple(float(v) for v in z), np.array(om, dtype=float))  # type: ignore[arg-type]
        for i, j, z, om in raw
    ]


def graph_inputs() -> Any:
    """Synthetic graphs of 2–12 poses with 0–4 loop closures (see ``posegraph.simulate``), and an
    iteration count that converges them."""
    from hypothesis import strategies as st

    def build(seed: int, n: int, loops: int, iterations: int) -> dict[str, Any]:
        poses, edges = pg.simulate(seed, n, loops if n > 2 else 0)
        return {"poses": poses.tolist(), "edges": _plain_edges(edges), "iterations": iterations}

    return st.builds(
        build,
        st.integers(0, 2**32 - 1),
        st.integers(2, 12),
        st.integers(0, 4),
        st.sampled_from([10, 15]),
    )


def gauss_newton(poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int) -> Matrix:
    """The poses after ``iterations`` Gauss-Newton steps, each seen from pose 0 (n×3)."""
    x, _ = pg.gauss_newton(np.array(poses, dtype=float), _edges(edges), int(iterations))
    return pg.relative_to_first(x)


def mistake_gn_absolute(poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int) -> Matrix:
    """The optimised poses in the world frame, not seen from pose 0."""
    x, _ = pg.gauss_newton(np.array(poses, dtype=float), _edges(edges), int(iterations))
    return x


def mistake_gn_no_step(poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int) -> Matrix:
    """The initial guess, unchanged."""
    return pg.relative_to_first(np.array(poses, dtype=float))


def _gn_variant(
    poses: Sequence[Pose],
    edges: Sequence[Sequence[Any]],
    iterations: int,
    *,
    wrap_error: bool = True,
    heading_sign: float = 1.0,
) -> Matrix:
    """Gauss-Newton written edge by edge, with one of two classic bugs switched on."""
    x = np.array(poses, dtype=float)
    n = len(x)
    for _ in range(int(iterations)):
        h = np.zeros((3 * n, 3 * n))
        g = np.zeros(3 * n)
        for i, j, z, om in edges:
            om = np.asarray(om, dtype=float)
            e = pg.edge_error(x[i], x[j], z)
            if not wrap_error:
                e[2] = x[j, 2] - x[i, 2] - float(z[2])
            a, b = pg.edge_jacobians(x[i], x[j], z)
            a[:2, 2] *= heading_sign
            si, sj = slice(3 * i, 3 * i + 3), slice(3 * j, 3 * j + 3)
            h[si, si] += a.T @ om @ a
            h[si, sj] += a.T @ om @ b
            h[sj, si] += b.T @ om @ a
            h[sj, sj] += b.T @ om @ b
            g[si] += a.T @ om @ e
            g[sj] += b.T @ om @ e
        x[1:] += np.linalg.solve(h[3:, 3:], -g[3:]).reshape(-1, 3)
        x[:, 2] = [se2.wrap_angle(t) for t in x[:, 2]]
    return pg.relative_to_first(x)


def mistake_gn_no_wrap(poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int) -> Matrix:
    """The angular error ``θ_j − θ_i − θ_z`` left unwrapped."""
    return _gn_variant(poses, edges, iterations, wrap_error=False)


def mistake_gn_jacobian_sign(
    poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int
) -> Matrix:
    """``∂e_xy/∂θ_i`` with the wrong sign."""
    return _gn_variant(poses, edges, iterations, heading_sign=-1.0)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def edge_valid(xi: Pose, xj: Pose, z: Pose) -> bool:
    """``edge_error``'s (and ``edge_jacobians``') domain: poses with positions in [−20, 20] m
    and headings in [−π, π], a measurement with positions in [−5, 5] m and an angle in
    [−π, π]."""
    if len(xi) != 3 or len(xj) != 3 or len(z) != 3:
        return False
    poses_ok = all(abs(p[0]) <= 20 and abs(p[1]) <= 20 and abs(p[2]) <= math.pi for p in (xi, xj))
    return poses_ok and abs(z[0]) <= 5 and abs(z[1]) <= 5 and abs(z[2]) <= math.pi


def graph_valid(poses: Sequence[Pose], edges: Sequence[Sequence[Any]], iterations: int) -> bool:
    """``gauss_newton``'s domain: 2–12 poses, edges between two of them with a symmetric
    positive-definite information matrix, every pose connected to pose 0, and a graph that
    converges within ``iterations`` steps (or ``iterations`` = 0: the initial guess). Before
    convergence the iterate depends on the gauge a correct method chooses (pose 0 removed, a
    strong prior on it, another pose fixed), which the prompt does not fix."""
    n = len(poses)
    if not 2 <= n <= 12 or not 0 <= iterations <= 20 or any(len(p) != 3 for p in poses):
        return False
    reached = {0}
    for e in edges:
        if len(e) != 4:
            return False
        i, j, z, om = e
        if not (0 <= i < n and 0 <= j < n) or i == j or len(z) != 3:
            return False
        a = np.asarray(om, dtype=float)
        if a.shape != (3, 3) or not np.allclose(a, a.T, atol=1e-12):
            return False
        try:
            np.linalg.cholesky(a)
        except np.linalg.LinAlgError:
            return False
    for _ in range(n):  # connectivity: every pose reachable from pose 0
        for e in edges:
            if e[0] in reached or e[1] in reached:
                reached |= {int(e[0]), int(e[1])}
    if len(reached) != n:
        return False
    if iterations == 0:
        return True
    x, _ = pg.gauss_newton(np.array(poses, dtype=float), _edges(edges), int(iterations))
    y, _ = pg.gauss_newton(x, _edges(edges), 3)
    return bool(np.max(np.abs(pg.relative_to_first(x) - pg.relative_to_first(y))) < 1e-8)
