"""Damped and robust pose-graph optimisation: Levenberg-Marquardt and robust kernels.

Conventions (those of :mod:`slamcourse.slam.posegraph`, plus):

- a **robust kernel** ``ρ`` is applied to each edge's squared Mahalanobis error
  ``s = eᵀ Ω e`` (dimensionless), not to the norm ``√s``; the cost is ``Σ ρ(s)`` over the edges
  and ``ρ(s) = s`` (plain least squares, kernel ``"l2"``) gives back ``χ²``;
- the kernel's **weight** is ``w(s) = ρ'(s)``; iteratively reweighted least squares (IRLS)
  computes ``w`` of every edge at the current poses and takes one Gauss-Newton step in which
  each edge's ``Ω`` is replaced by ``w Ω``;
- the kernels, with width ``k > 0`` (the boundary is at ``s = k²``, one edge ``k`` standard
  deviations off):

  ============  ===========================================  =====================================
  kernel        ``ρ(s)``                                     ``w(s) = ρ'(s)``
  ============  ===========================================  =====================================
  ``l2``        ``s``                                        ``1``
  ``huber``     ``s`` if ``s ≤ k²``, else ``2k√s − k²``       ``1`` if ``s ≤ k²``, else ``k/√s``
  ``cauchy``    ``k² ln(1 + s/k²)``                          ``1 / (1 + s/k²)``
  ``dcs``       ``s`` if ``s ≤ Φ``, else ``Φ(3s − Φ)/(Φ + s)`` ``min(1, 2Φ/(Φ + s))²``
  ============  ===========================================  =====================================

  with ``Φ = k²`` for dynamic covariance scaling (DCS, Agarwal, Tipaldi, Spinello, Stachniss and
  Burgard, ICRA 2013): their scale ``min(1, 2Φ/(Φ + s))`` multiplies the error, so ``Ω`` is
  multiplied by its square;
- Levenberg-Marquardt solves ``(H + λ D) Δ = −b`` with ``D = diag(H)`` (Marquardt) or ``D = I``
  (Levenberg), pose 0 held fixed, and judges the step by the **gain ratio**
  ``ϱ = (χ²(x) − χ²(x + Δ)) / (χ²(x) − L(Δ))``, ``L(Δ) = Σ (e + JΔ)ᵀ Ω (e + JΔ)`` the
  linearised χ² (so the predicted reduction is ``−Δᵀ(2b + HΔ)``... written out in
  :func:`predicted_reduction`). A step with ``ϱ > 0`` is accepted and ``λ`` shrinks; otherwise
  the poses stay and ``λ`` grows (Nielsen's rule, :func:`levenberg_marquardt`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import posegraph as pg
from slamcourse.slam.se2 import wrap_angle

KERNELS = ("l2", "huber", "cauchy", "dcs")

Array = NDArray[np.float64]


# --- kernels ----------------------------------------------------------------------------------


def _check(kind: str, k: float) -> None:
    if kind not in KERNELS:
        raise ValueError(f"unknown kernel {kind!r}; one of {', '.join(KERNELS)}")
    if not k > 0:
        raise ValueError(f"the kernel width k must be positive, got {k}")


def kernel_cost(kind: str, s: ArrayLike, k: float) -> Array:
    """``ρ(s)`` of every entry of ``s`` (squared Mahalanobis errors, ≥ 0), same shape."""
    _check(kind, k)
    s = np.asarray(s, dtype=float)
    k2 = float(k) ** 2
    if kind == "l2":
        return s.copy()
    if kind == "huber":
        return np.where(s <= k2, s, 2.0 * k * np.sqrt(np.maximum(s, k2)) - k2)
    if kind == "cauchy":
        return k2 * np.log1p(s / k2)
    return np.where(s <= k2, s, k2 * (3.0 * s - k2) / (k2 + s))


def kernel_weights(kind: str, s: ArrayLike, k: float) -> Array:
    """``w(s) = ρ'(s)`` of every entry of ``s`` (squared Mahalanobis errors, ≥ 0), same shape;
    each in (0, 1], 1 where ``s ≤ k²`` for Huber and DCS and at ``s = 0`` for all."""
    _check(kind, k)
    s = np.asarray(s, dtype=float)
    k2 = float(k) ** 2
    if kind == "l2":
        return np.ones_like(s)
    if kind == "huber":
        return np.where(s <= k2, 1.0, k / np.sqrt(np.maximum(s, k2)))
    if kind == "cauchy":
        return 1.0 / (1.0 + s / k2)
    return np.minimum(1.0, 2.0 * k2 / (k2 + s)) ** 2


# --- per-edge errors and weighted Gauss-Newton ------------------------------------------------


def edge_chi2s(poses: ArrayLike, edges: Sequence[pg.Edge]) -> Array:
    """``s = eᵀ Ω e`` of every edge at ``poses`` (n×3), in the edges' order."""
    if not edges:
        return np.zeros(0)
    e, _, _, om = pg.stacked_errors(np.asarray(poses, dtype=float), edges)
    return np.asarray(np.einsum("ki,kij,kj->k", e, om, e), dtype=float)


def loop_closures(edges: Sequence[pg.Edge]) -> NDArray[np.bool_]:
    """Which edges are loop closures: those whose poses are not consecutive (``|i − j| ≠ 1``)."""
    return np.array([abs(e.i - e.j) != 1 for e in edges], dtype=bool)


def edge_weights(
    poses: ArrayLike, edges: Sequence[pg.Edge], kind: str, k: float, everywhere: bool = False
) -> Array:
    """The IRLS weight of every edge at ``poses``: ``w(s)`` for loop closures and 1 for odometry
    edges (which are trusted), or ``w(s)`` for every edge with ``everywhere``."""
    w = kernel_weights(kind, edge_chi2s(poses, edges), k)
    return w if everywhere else np.where(loop_closures(edges), w, 1.0)


def robust_cost(
    poses: ArrayLike, edges: Sequence[pg.Edge], kind: str, k: float, everywhere: bool = False
) -> float:
    """``Σ ρ(eᵀ Ω e)`` over the loop closures plus ``Σ eᵀ Ω e`` over the odometry edges (or
    ``ρ`` on every edge with ``everywhere``)."""
    s = edge_chi2s(poses, edges)
    robust = kernel_cost(kind, s, k)
    return float(np.sum(robust if everywhere else np.where(loop_closures(edges), robust, s)))


def _weighted(weights: Array) -> pg.ErrorModel:
    """The course's error model with every edge's information multiplied by its weight."""

    def model(x: Array, edges: Sequence[pg.Edge]) -> pg.Stacked:
        e, a, b, om = pg.stacked_errors(x, edges)
        return e, a, b, om * weights[:, None, None]

    return model


def irls_step(
    poses: ArrayLike,
    edges: Sequence[pg.Edge],
    kind: str,
    k: float,
    anchor: int = 0,
    everywhere: bool = False,
) -> Array:
    """One IRLS step: the weights at ``poses`` (:func:`edge_weights`), then one Gauss-Newton
    step with each ``Ω`` scaled by its edge's weight (pose ``anchor`` fixed). Returns the new
    poses (n×3)."""
    x = np.asarray(poses, dtype=float)
    w = edge_weights(x, edges, kind, k, everywhere)
    return pg.gauss_newton_step(x, edges, anchor, _weighted(w))


def irls(
    poses: ArrayLike,
    edges: Sequence[pg.Edge],
    kind: str,
    k: float,
    iterations: int,
    anchor: int = 0,
    everywhere: bool = False,
) -> tuple[Array, list[float]]:
    """``iterations`` IRLS steps from ``poses``; returns the poses and the robust cost
    (:func:`robust_cost`) before each step and after the last."""
    x = np.array(poses, dtype=float)
    history = [robust_cost(x, edges, kind, k, everywhere)]
    for _ in range(int(iterations)):
        x = irls_step(x, edges, kind, k, anchor, everywhere)
        history.append(robust_cost(x, edges, kind, k, everywhere))
    return x, history


# --- Levenberg-Marquardt ----------------------------------------------------------------------


def _reduced_system(
    x: Array, edges: Sequence[pg.Edge], anchor: int
) -> tuple[object, Array, NDArray[np.bool_]]:
    """The sparse ``H`` and dense ``b`` of all poses but ``anchor`` (csc matrix, vector) and the
    mask of the unknowns kept."""
    from scipy.sparse import csc_matrix  # type: ignore[import-untyped]

    rows, cols, values, g = pg._system_entries(x, edges)
    n3 = len(g)
    h = csc_matrix((values, (rows, cols)), shape=(n3, n3))
    keep = np.ones(n3, dtype=bool)
    keep[3 * anchor : 3 * anchor + 3] = False
    return h[keep][:, keep], g[keep], keep


def predicted_reduction(h: object, b: Array, delta: Array) -> float:
    """``χ²(x) − L(Δ) = −(2 bᵀΔ + Δᵀ H Δ)``: the reduction the linearised model promises."""
    hd: Array = np.asarray(h @ delta, dtype=np.float64)  # type: ignore[operator]
    return float(-(2.0 * float(b @ delta) + float(delta @ hd)))


def damped_step(
    poses: ArrayLike,
    edges: Sequence[pg.Edge],
    lam: float,
    marquardt: bool = True,
    anchor: int = 0,
) -> tuple[Array, float]:
    """Solve ``(H + λ D) Δ = −b`` (``D = diag H`` or ``I``) at ``poses``; returns the candidate
    poses (angles wrapped) and the predicted reduction of χ²."""
    from scipy.sparse import diags
    from scipy.sparse.linalg import spsolve  # type: ignore[import-untyped]

    x = np.array(poses, dtype=float)
    h, b, keep = _reduced_system(x, edges, anchor)
    d = h.diagonal() if marquardt else np.ones(len(b))  # type: ignore[attr-defined]
    delta = np.asarray(spsolve((h + diags(lam * d)).tocsc(), -b), dtype=float)
    full = np.zeros(len(keep))
    full[keep] = delta
    y = x + full.reshape(-1, 3)
    y[:, 2] = [wrap_angle(t) for t in y[:, 2]]
    return y, predicted_reduction(h, b, delta)


def gain_ratio(before: float, after: float, predicted: float) -> float:
    """``ϱ = (χ² before − χ² after) / predicted reduction``."""
    return (before - after) / predicted


def levenberg_marquardt(
    poses: ArrayLike,
    edges: Sequence[pg.Edge],
    iterations: int,
    lambda0: float,
    marquardt: bool = True,
    anchor: int = 0,
) -> tuple[Array, list[float], list[float]]:
    """``iterations`` Levenberg-Marquardt trials (each one linear solve) from ``poses``.

    A trial with gain ratio ``ϱ > 0`` is accepted and ``λ ← λ · max(1/3, 1 − (2ϱ − 1)³)``,
    ``ν ← 2``; a rejected one keeps the poses and sets ``λ ← λ ν``, ``ν ← 2ν`` (Nielsen 1999,
    as in Madsen, Nielsen and Tingleff's notes). Returns the poses, χ² after every trial
    (the first entry before any) and λ used by every trial.
    """
    x = np.array(poses, dtype=float)
    current = pg.chi2(x, edges)
    history, lambdas = [current], []
    lam, nu = float(lambda0), 2.0
    for _ in range(int(iterations)):
        lambdas.append(lam)
        y, predicted = damped_step(x, edges, lam, marquardt, anchor)
        new = pg.chi2(y, edges)
        rho = gain_ratio(current, new, predicted) if predicted > 0 else -1.0
        if rho > 0:
            x, current = y, new
            lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            nu = 2.0
        else:
            lam *= nu
            nu *= 2.0
        history.append(current)
    return x, history, lambdas


# --- outliers ---------------------------------------------------------------------------------


def false_loop_closures(
    poses: ArrayLike,
    edges: Sequence[pg.Edge],
    count: int,
    seed: int,
    min_gap: int = 50,
) -> list[pg.Edge]:
    """``count`` wrong loop closures for the graph ``(poses, edges)``, seeded.

    Each joins two poses ``i < j`` drawn uniformly with ``j − i ≥ min_gap`` (never neighbours
    in time), measures a plausible but wrong relative pose (``dx``, ``dy`` uniform in
    [−2, 2] m, ``dθ`` uniform in [−π, π)), and carries the information matrix of one of the
    graph's own loop closures (an edge with ``|i − j| > 1``; of any edge if there is none),
    drawn at random: as confident as a real scan match. ``numpy.random.default_rng(seed)``
    draws, per edge in turn: ``i``, ``j``, ``dx``, ``dy``, ``dθ``, the information's source.
    """
    rng = np.random.default_rng(seed)
    n = len(np.asarray(poses))
    if n <= min_gap:
        raise ValueError(f"a graph of {n} poses has no pair {min_gap} or more apart")
    sources = [e for e in edges if abs(e.i - e.j) > 1] or list(edges)
    out = []
    for _ in range(int(count)):
        i = int(rng.integers(0, n - min_gap))
        j = int(rng.integers(i + min_gap, n))
        dx, dy = (float(v) for v in rng.uniform(-2.0, 2.0, size=2))
        dt = float(rng.uniform(-math.pi, math.pi))
        info = sources[int(rng.integers(0, len(sources)))].information
        out.append(pg.Edge(i, j, (dx, dy, dt), np.array(info, dtype=float)))
    return out


def position_error(a: ArrayLike, b: ArrayLike) -> float:
    """RMS distance (m) between the positions of two solutions, each seen from its pose 0."""
    ra, rb = pg.relative_to_first(a), pg.relative_to_first(b)
    return float(np.sqrt(np.mean(np.sum((ra[:, :2] - rb[:, :2]) ** 2, axis=1))))
