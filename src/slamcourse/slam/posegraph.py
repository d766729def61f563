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
from collections.abc import Sequence
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


def chi2(poses: ArrayLike, edges: Sequence[Edge]) -> float:
    """``Σ eᵀ Ω e`` over all edges (dimensionless)."""
    x = np.asarray(poses, dtype=float)
    total = 0.0
    for edge in edges:
        e = edge_error(x[edge.i], x[edge.j], edge.z)
        total += float(e @ edge.information @ e)
    return total


def linear_system(
    poses: ArrayLike, edges: Sequence[Edge]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``H = Σ Jᵀ Ω J`` (3n×3n) and ``b = Σ Jᵀ Ω e`` (3n) at ``poses``, without any anchor."""
    x = np.asarray(poses, dtype=float)
    n = len(x)
    h = np.zeros((3 * n, 3 * n))
    g = np.zeros(3 * n)
    for edge in edges:
        e = edge_error(x[edge.i], x[edge.j], edge.z)
        a, b = edge_jacobians(x[edge.i], x[edge.j], edge.z)
        om = edge.information
        si, sj = slice(3 * edge.i, 3 * edge.i + 3), slice(3 * edge.j, 3 * edge.j + 3)
        h[si, si] += a.T @ om @ a
        h[si, sj] += a.T @ om @ b
        h[sj, si] += b.T @ om @ a
        h[sj, sj] += b.T @ om @ b
        g[si] += a.T @ om @ e
        g[sj] += b.T @ om @ e
    return h, g


def gauss_newton_step(
    poses: ArrayLike, edges: Sequence[Edge], anchor: int = 0
) -> NDArray[np.float64]:
    """One undamped Gauss-Newton step with pose ``anchor`` held fixed; returns the new poses."""
    x = np.array(poses, dtype=float)
    h, g = linear_system(x, edges)
    keep = np.ones(3 * len(x), dtype=bool)
    keep[3 * anchor : 3 * anchor + 3] = False
    delta = np.zeros(3 * len(x))
    delta[keep] = np.linalg.solve(h[np.ix_(keep, keep)], -g[keep])
    x += delta.reshape(-1, 3)
    x[:, 2] = [wrap_angle(t) for t in x[:, 2]]
    return x


def gauss_newton(
    poses: ArrayLike, edges: Sequence[Edge], iterations: int, anchor: int = 0
) -> tuple[NDArray[np.float64], list[float]]:
    """``iterations`` Gauss-Newton steps; returns the poses and χ² before each step and after."""
    x = np.array(poses, dtype=float)
    history = [chi2(x, edges)]
    for _ in range(iterations):
        x = gauss_newton_step(x, edges, anchor)
        history.append(chi2(x, edges))
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
