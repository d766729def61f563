"""Pose-graph SLAM in the plane: edge errors, their Jacobians, and Gauss-Newton.

Conventions (those of g2o and of the Freiburg course, stated once for the whole course):

- a graph has ``n`` poses ``x_i = (x, y, θ)`` and edges ``(i, j, z, Ω)``: a measurement
  ``z = (dx, dy, dθ)`` of pose ``j`` seen from pose ``i``, with 3×3 information matrix ``Ω``;
- the error of an edge is ``e = t2v(Z⁻¹ · X_i⁻¹ · X_j)``, i.e. ``z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)``, with its
  angle wrapped into (−π, π]; it is zero when the poses agree with the measurement;
- ``χ² = Σ eᵀ Ω e`` over the edges (GTSAM prints half of this);
- Gauss-Newton linearises ``e(x ⊞ Δ) ≈ e + A Δ_i + B Δ_j`` with the additive update
  ``x ⊞ Δ = x + Δ`` (angles re-wrapped), builds ``H = Σ Jᵀ Ω J`` and ``b = Σ Jᵀ Ω e`` and
  solves ``H Δ = −b`` with pose 0 held fixed (the gauge).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam.se2 import between, compose, inverse, wrap_angle


@dataclass(frozen=True)
class Edge:
    """One relative-pose measurement ``z`` of pose ``j`` from pose ``i`` with information ``Ω``."""

    i: int
    j: int
    z: tuple[float, float, float]
    information: NDArray[np.float64]  # 3×3, symmetric positive definite


Stacked = tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]
# errors (m×3), A and B (m×3×3) and informations (m×3×3) of all edges at the poses (n×3)
ErrorModel = Callable[[NDArray[np.float64], Sequence[Edge]], Stacked]


@dataclass(frozen=True)
class PoseGraph:
    """Poses (n×3 array: x, y in metres, θ in radians) and edges."""

    poses: NDArray[np.float64]
    edges: tuple[Edge, ...]


def edge_error(xi: Sequence[float], xj: Sequence[float], z: Sequence[float]) -> NDArray[np.float64]:
    """``e = z⁻¹ ⊕ (x_i⁻¹ ⊕ x_j)``, shape (3,), angle wrapped into (−π, π]."""
    return np.array(compose(inverse(z), between(xi, xj)))


def edge_jacobians(
    xi: Sequence[float], xj: Sequence[float], z: Sequence[float]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``A = ∂e/∂x_i`` and ``B = ∂e/∂x_j`` (each 3×3) of :func:`edge_error`.

    With ``R_i``, ``R_z`` the rotations of ``x_i`` and ``z`` and ``t_i``, ``t_j`` the positions,
    ``e_xy = R_zᵀ (R_iᵀ (t_j − t_i) − t_z)`` and ``e_θ = θ_j − θ_i − θ_z``.
    """
    ti, tj = np.array(xi[:2], dtype=float), np.array(xj[:2], dtype=float)
    ci, si = math.cos(float(xi[2])), math.sin(float(xi[2]))
    cz, sz = math.cos(float(z[2])), math.sin(float(z[2]))
    ri_t = np.array([[ci, si], [-si, ci]])  # R_iᵀ
    rz_t = np.array([[cz, sz], [-sz, cz]])  # R_zᵀ
    d_ri_t = np.array([[-si, ci], [-ci, -si]])  # d(R_iᵀ)/dθ_i
    a = np.zeros((3, 3))
    b = np.zeros((3, 3))
    a[:2, :2] = -rz_t @ ri_t
    a[:2, 2] = rz_t @ d_ri_t @ (tj - ti)
    a[2, 2] = -1.0
    b[:2, :2] = rz_t @ ri_t
    b[2, 2] = 1.0
    return a, b


def chi2(poses: ArrayLike, edges: Sequence[Edge], model: ErrorModel | None = None) -> float:
    """``Σ eᵀ Ω e`` over all edges (dimensionless); ``model`` defaults to :func:`stacked_errors`."""
    if not edges:
        return 0.0
    e, _, _, om = (model or stacked_errors)(np.asarray(poses, dtype=float), edges)
    return float(np.einsum("ki,kij,kj->", e, om, e))


def stacked_errors(x: NDArray[np.float64], edges: Sequence[Edge]) -> Stacked:
    """All edges at once: errors (m×3), Jacobians A and B (m×3×3) and informations (m×3×3).

    ``x`` is the n×3 array of poses; the edges' order is kept.

    The same formulas as :func:`edge_error` and :func:`edge_jacobians`, vectorised over edges.
    """
    i = np.array([edge.i for edge in edges])
    j = np.array([edge.j for edge in edges])
    z = np.array([edge.z for edge in edges], dtype=float)
    om = np.array([edge.information for edge in edges], dtype=float)
    ci, si = np.cos(x[i, 2]), np.sin(x[i, 2])
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    d = x[j, :2] - x[i, :2]
    # R_iᵀ d, then R_zᵀ (R_iᵀ d − t_z)
    lx, ly = ci * d[:, 0] + si * d[:, 1], -si * d[:, 0] + ci * d[:, 1]
    ux, uy = lx - z[:, 0], ly - z[:, 1]
    e = np.stack([cz * ux + sz * uy, -sz * ux + cz * uy, x[j, 2] - x[i, 2] - z[:, 2]], axis=1)
    e[:, 2] = np.remainder(e[:, 2] + np.pi, 2 * np.pi) - np.pi
    e[:, 2][e[:, 2] == -np.pi] = np.pi
    m = len(edges)
    rzri = np.empty((m, 2, 2))  # R_zᵀ R_iᵀ = R(θ_i + θ_z)ᵀ
    c, s = np.cos(x[i, 2] + z[:, 2]), np.sin(x[i, 2] + z[:, 2])
    rzri[:, 0, 0], rzri[:, 0, 1], rzri[:, 1, 0], rzri[:, 1, 1] = c, s, -s, c
    dlx, dly = -si * d[:, 0] + ci * d[:, 1], -ci * d[:, 0] - si * d[:, 1]  # d(R_iᵀ)/dθ · d
    a = np.zeros((m, 3, 3))
    b = np.zeros((m, 3, 3))
    a[:, :2, :2] = -rzri
    a[:, 0, 2] = cz * dlx + sz * dly
    a[:, 1, 2] = -sz * dlx + cz * dly
    a[:, 2, 2] = -1.0
    b[:, :2, :2] = rzri
    b[:, 2, 2] = 1.0
    return e, a, b, om


def linear_system(
    poses: ArrayLike, edges: Sequence[Edge]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``H = Σ Jᵀ Ω J`` (dense, 3n×3n) and ``b = Σ Jᵀ Ω e`` (3n) at ``poses``, without an anchor."""
    rows, cols, values, g = _system_entries(poses, edges)
    n3 = len(g)
    h = np.zeros((n3, n3))
    np.add.at(h, (rows, cols), values)
    return h, g


def _system_entries(
    poses: ArrayLike, edges: Sequence[Edge], model: ErrorModel | None = None
) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.float64], NDArray[np.float64]]:
    """The blocks of ``H`` as coordinate triplets (rows, cols, values; repeated cells add up)
    and the dense gradient ``b``."""
    x = np.asarray(poses, dtype=float)
    n = len(x)
    g = np.zeros(3 * n)
    if not edges:
        empty = np.zeros(0, dtype=np.intp)
        return empty, empty, np.zeros(0), g
    e, a, b, om = (model or stacked_errors)(x, edges)
    i = np.array([edge.i for edge in edges])
    j = np.array([edge.j for edge in edges])
    at_om, bt_om = np.einsum("kji,kjl->kil", a, om), np.einsum("kji,kjl->kil", b, om)
    np.add.at(g, 3 * i[:, None] + np.arange(3), np.einsum("kij,kj->ki", at_om, e))
    np.add.at(g, 3 * j[:, None] + np.arange(3), np.einsum("kij,kj->ki", bt_om, e))
    rows, cols, values = [], [], []
    offsets = np.arange(3)
    for p, q, block in ((i, i, at_om @ a), (i, j, at_om @ b), (j, i, bt_om @ a), (j, j, bt_om @ b)):
        rows.append((3 * p[:, None, None] + offsets[None, :, None] + 0 * offsets).ravel())
        cols.append((3 * q[:, None, None] + 0 * offsets[:, None] + offsets[None, None, :]).ravel())
        values.append(block.ravel())
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(values), g


def gauss_newton_step(
    poses: ArrayLike, edges: Sequence[Edge], anchor: int = 0, model: ErrorModel | None = None
) -> NDArray[np.float64]:
    """One undamped Gauss-Newton step with pose ``anchor`` held fixed; returns the new poses.

    ``H`` is assembled and factorised as a sparse matrix (scipy), so that a graph of a few
    thousand poses takes milliseconds; the result equals a dense solve. ``model`` (errors and
    Jacobians of all edges) defaults to :func:`stacked_errors`, this module's convention.
    """
    from scipy.sparse import csc_matrix  # type: ignore[import-untyped]
    from scipy.sparse.linalg import spsolve  # type: ignore[import-untyped]

    x = np.array(poses, dtype=float)
    rows, cols, values, g = _system_entries(x, edges, model)
    n3 = len(g)
    h = csc_matrix((values, (rows, cols)), shape=(n3, n3))
    keep = np.ones(n3, dtype=bool)
    keep[3 * anchor : 3 * anchor + 3] = False
    delta = np.zeros(n3)
    delta[keep] = spsolve(h[keep][:, keep], -g[keep])
    x += delta.reshape(-1, 3)
    x[:, 2] = [wrap_angle(t) for t in x[:, 2]]
    return x


def gauss_newton(
    poses: ArrayLike,
    edges: Sequence[Edge],
    iterations: int,
    anchor: int = 0,
    model: ErrorModel | None = None,
) -> tuple[NDArray[np.float64], list[float]]:
    """``iterations`` Gauss-Newton steps; returns the poses and χ² before each step and after."""
    x = np.array(poses, dtype=float)
    history = [chi2(x, edges, model)]
    for _ in range(iterations):
        x = gauss_newton_step(x, edges, anchor, model)
        history.append(chi2(x, edges, model))
    return x, history


def relative_to_first(poses: ArrayLike) -> NDArray[np.float64]:
    """Every pose seen from pose 0 (``x_0⁻¹ ⊕ x_i``), n×3: a gauge-free summary of a solution."""
    x = np.asarray(poses, dtype=float)
    return np.array([between(x[0], p) for p in x])


def information_from_upper(values: Sequence[float]) -> NDArray[np.float64]:
    """The symmetric 3×3 ``Ω`` from g2o's upper triangle ``I11 I12 I13 I22 I23 I33``."""
    i11, i12, i13, i22, i23, i33 = (float(v) for v in values)
    return np.array([[i11, i12, i13], [i12, i22, i23], [i13, i23, i33]])


def parse_g2o(text: str) -> PoseGraph:
    """Read a 2-D g2o file.

    Records: ``VERTEX_SE2 id x y θ`` and ``EDGE_SE2 i j dx dy dθ I11 I12 I13 I22 I23 I33``.

    Vertex ids must be 0…n−1 (in any order). Blank lines and other record types are skipped.
    """
    vertices: dict[int, tuple[float, float, float]] = {}
    edges = []
    for line in text.splitlines():
        fields = line.split()
        if not fields:
            continue
        if fields[0] == "VERTEX_SE2":
            vertices[int(fields[1])] = (float(fields[2]), float(fields[3]), float(fields[4]))
        elif fields[0] == "EDGE_SE2":
            z = (float(fields[3]), float(fields[4]), float(fields[5]))
            edges.append(
                Edge(
                    int(fields[1]),
                    int(fields[2]),
                    z,
                    information_from_upper([float(v) for v in fields[6:12]]),
                )
            )
    poses = np.array([vertices[k] for k in range(len(vertices))], dtype=float).reshape(-1, 3)
    return PoseGraph(poses, tuple(edges))


def before_after(
    text: str, iterations: int = 10
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """For plotting: a g2o graph's initial poses and its poses after Gauss-Newton (n×3 each).

    Pose 0 is held fixed, so both trajectories share its frame and can be drawn on one figure.
    """
    graph = parse_g2o(text)
    optimised, _ = gauss_newton(graph.poses, graph.edges, iterations)
    return graph.poses.copy(), optimised


def simulate(
    seed: int,
    n: int,
    loops: int,
    noise: tuple[float, float] = (0.05, 0.02),
    correlated: bool = True,
) -> tuple[NDArray[np.float64], tuple[Edge, ...]]:
    """A small synthetic graph: a random walk of ``n`` poses, its noisy odometry edges and
    ``loops`` noisy loop closures between random pairs of poses.

    Returns the initial guess (dead reckoning from the noisy odometry, placed at a random pose in
    the world, angles wrapped) and the edges. ``noise`` is the standard deviation of the
    measurement noise in metres and radians; each edge's information is a random symmetric
    positive-definite matrix of about that precision (with off-diagonal terms if
    ``correlated``). Headings wander freely, so they cross ±π.
    """
    rng = np.random.default_rng(seed)
    sxy, st = noise
    truth = [(0.0, 0.0, float(rng.uniform(-math.pi, math.pi)))]
    for _ in range(n - 1):
        step = (float(rng.uniform(0.5, 2.0)), float(rng.uniform(-0.5, 0.5)), 0.0)
        step = (step[0], step[1], float(rng.uniform(-1.2, 1.2)))
        truth.append(compose(truth[-1], step))
    pairs = [(k, k + 1) for k in range(n - 1)]
    for _ in range(loops):
        i, j = (int(v) for v in rng.choice(n, size=2, replace=False))
        pairs.append((i, j))
    edges = []
    for i, j in pairs:
        true_z = between(truth[i], truth[j])
        z = (
            true_z[0] + float(rng.normal(0, sxy)),
            true_z[1] + float(rng.normal(0, sxy)),
            wrap_angle(true_z[2] + float(rng.normal(0, st))),
        )
        scale = np.diag([1 / sxy, 1 / sxy, 1 / st])
        mix = np.eye(3) + (rng.uniform(-0.3, 0.3, size=(3, 3)) if correlated else 0.0)
        root = mix @ scale
        edges.append(Edge(i, j, z, root.T @ root))
    # dead reckoning from the odometry edges, from a random start in the world
    start = (float(rng.uniform(-10, 10)), float(rng.uniform(-10, 10)), float(rng.uniform(-3, 3)))
    guess = [start]
    for edge in edges[: n - 1]:
        guess.append(compose(guess[-1], edge.z))
    return np.array(guess, dtype=float).reshape(-1, 3), tuple(edges)


def to_g2o(poses: ArrayLike, edges: Sequence[Edge]) -> str:
    """A graph as g2o text (``VERTEX_SE2`` and ``EDGE_SE2`` lines; upper-triangle information)."""
    lines = [
        f"VERTEX_SE2 {k} {float(x)!r} {float(y)!r} {float(t)!r}"
        for k, (x, y, t) in enumerate(np.asarray(poses))
    ]
    for edge in edges:
        om = edge.information
        upper = (om[0, 0], om[0, 1], om[0, 2], om[1, 1], om[1, 2], om[2, 2])
        values = " ".join(repr(float(v)) for v in (*edge.z, *upper))
        lines.append(f"EDGE_SE2 {int(edge.i)} {int(edge.j)} {values}")
    return "\n".join(lines) + "\n"
