"""Reference code for chapter ``scan-matching``: closed-form alignment, ICP, ray casting.

Points are ``(N, 2)`` lists in metres; ``align_2d`` returns ``[θ, t_x, t_y]`` (radians, metres)
of the rigid motion with ``q_i ≈ R(θ) p_i + t``. Grid cells are integer pairs ``[x, y]``. The
mathematics lives in :mod:`slamcourse.slam.scanmatch` and :mod:`slamcourse.slam.raycast`.
Functions whose name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from slamcourse.slam import raycast, scanmatch

Points = Sequence[Sequence[float]]


# --- numeric: the angle from two correspondences -------------------------------------------------


def _two_points(p1x: float, p1y: float, p2x: float, p2y: float, theta: float, tx: float,
                ty: float) -> tuple[np.ndarray, np.ndarray]:
    p = np.array([[p1x, p1y], [p2x, p2y]])
    return p, p @ scanmatch.rotation(theta).T + np.array([tx, ty])


def two_point_angle(p1x: float, p1y: float, p2x: float, p2y: float, theta: float, tx: float,
                    ty: float, **_: float) -> float:
    p, q = _two_points(p1x, p1y, p2x, p2y, theta, tx, ty)
    return scanmatch.align_angle(p, q)[0]


def mistake_two_point_positions(p1x: float, p1y: float, p2x: float, p2y: float, theta: float,
                                tx: float, ty: float, **_: float) -> float:
    """The bearing of ``q₂`` minus that of ``p₂`` from the origin: the translation ignored."""
    _, q = _two_points(p1x, p1y, p2x, p2y, theta, tx, ty)
    return math.atan2(q[1, 1], q[1, 0]) - math.atan2(p2y, p2x)


def mistake_two_point_reversed(p1x: float, p1y: float, p2x: float, p2y: float, theta: float,
                               tx: float, ty: float, **_: float) -> float:
    return -two_point_angle(p1x, p1y, p2x, p2y, theta, tx, ty)


def mistake_two_point_degrees(p1x: float, p1y: float, p2x: float, p2y: float, theta: float,
                              tx: float, ty: float, **_: float) -> float:
    return math.degrees(two_point_angle(p1x, p1y, p2x, p2y, theta, tx, ty))


# --- numeric: cells of a beam, log-odds after hits ---------------------------------------------


def beam_cells(x0: int, y0: int, x1: int, y1: int) -> int:
    return len(raycast.bresenham(x0, y0, x1, y1))


def mistake_beam_cells_4connected(x0: int, y0: int, x1: int, y1: int) -> int:
    return abs(x1 - x0) + abs(y1 - y0) + 1


def mistake_beam_cells_no_start(x0: int, y0: int, x1: int, y1: int) -> int:
    return max(abs(x1 - x0), abs(y1 - y0))


def hit_cell_log_odds(k: int, m: int, l_occ: float, l_free: float, **_: float) -> float:
    value = raycast.log_odds_after_hits(0.0, l_occ, k)
    return value + m * l_free


def mistake_hits_ignore_free(k: int, m: int, l_occ: float, l_free: float, **_: float) -> float:
    return k * l_occ


def mistake_hits_averaged(k: int, m: int, l_occ: float, l_free: float, **_: float) -> float:
    return (k * l_occ + m * l_free) / (k + m)


def mistake_hits_probability(k: int, m: int, l_occ: float, l_free: float, **_: float) -> float:
    """The probability ``σ(l)`` instead of the log-odds."""
    return 1 / (1 + math.exp(-hit_cell_log_odds(k, m, l_occ, l_free)))


# --- code: align_2d ----------------------------------------------------------------------------


def align_2d(P: Points, Q: Points) -> list[float]:
    theta, t = scanmatch.align_angle(P, Q)
    return [theta, float(t[0]), float(t[1])]


def align_inputs() -> Any:
    """``P``: 2–10 points in [−20, 20]² m, not all within 0.5 m of their centroid. ``Q``: ``P``
    moved by a rigid motion (θ in (−π, π], t in [−5, 5]² m), plus one of: nothing, noise of
    0.02 m, noise of 1 m, or a mirror (``Q`` reflected), so that the unconstrained best fit is
    sometimes a reflection. Draws where the best angle is ill-defined are rejected."""
    from hypothesis import strategies as st

    coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
    cloud = st.lists(st.tuples(coord, coord), min_size=2, max_size=10)

    def make(args: tuple[Any, ...]) -> dict[str, Any]:
        pts, theta, tx, ty, mode, seed = args
        p = np.asarray(pts, dtype=float)
        q = p @ scanmatch.rotation(theta).T + np.array([tx, ty])
        rng = np.random.default_rng(seed)
        if mode == "mirror":
            q = q * np.array([1.0, -1.0])
        elif mode != "exact":
            q = q + rng.normal(0.0, float(mode), q.shape)
        return {"P": p.round(6).tolist(), "Q": q.round(6).tolist()}

    def well_posed(d: dict[str, Any]) -> bool:
        p = np.asarray(d["P"])
        _, _, h = scanmatch.cross_covariance(d["P"], d["Q"])
        spread = float(np.sum((p - p.mean(axis=0)) ** 2))
        return spread > 0.25 * len(p) and math.hypot(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1]) > 1e-3 * spread

    args = st.tuples(
        cloud,
        st.floats(-3.14159, 3.14159),
        st.floats(-5.0, 5.0),
        st.floats(-5.0, 5.0),
        st.sampled_from(["exact", "exact", "mirror", 0.02, 1.0]),
        st.integers(0, 2**31 - 1),
    )
    return args.map(make).filter(well_posed)


def mistake_align_reflection(P: Points, Q: Points) -> list[float]:
    """``R = V Uᵀ`` without the ``det`` correction; the angle read from the first column."""
    pm, qm, h = scanmatch.cross_covariance(P, Q)
    u, _, vt = np.linalg.svd(h)
    r = vt.T @ u.T
    t = qm - r @ pm
    return [math.atan2(r[1, 0], r[0, 0]), float(t[0]), float(t[1])]


def mistake_align_centroid_difference(P: Points, Q: Points) -> list[float]:
    """The right angle, but ``t = q̄ − p̄``: the centroid of ``P`` not rotated."""
    pm, qm, _ = scanmatch.cross_covariance(P, Q)
    theta, _ = scanmatch.align_angle(P, Q)
    t = qm - pm
    return [theta, float(t[0]), float(t[1])]


def mistake_align_transposed(P: Points, Q: Points) -> list[float]:
    """``R = U Vᵀ``: the rotation taking ``Q`` to ``P`` (the angle's sign flipped)."""
    pm, qm, _ = scanmatch.cross_covariance(P, Q)
    theta, _ = scanmatch.align_angle(P, Q)
    t = qm - scanmatch.rotation(-theta) @ pm
    return [-theta, float(t[0]), float(t[1])]


# --- code: bresenham ----------------------------------------------------------------------------


def bresenham(x0: int, y0: int, x1: int, y1: int) -> list[list[int]]:
    return [[x, y] for x, y in raycast.bresenham(x0, y0, x1, y1)]


def mistake_bresenham_round_half_even(x0: int, y0: int, x1: int, y1: int) -> list[list[int]]:
    """Python's ``round`` (ties to the even integer) on the exact line."""
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 + round(k * dx / n), y0 + round(k * dy / n)] for k in range(n + 1)]


def mistake_bresenham_no_end(x0: int, y0: int, x1: int, y1: int) -> list[list[int]]:
    """The end cell left out."""
    return bresenham(x0, y0, x1, y1)[:-1] or [[x0, y0]]


def mistake_bresenham_ties_down(x0: int, y0: int, x1: int, y1: int) -> list[list[int]]:
    """Ties rounded towards the smaller coordinate (``⌈v − 1/2⌉``)."""
    dx, dy = x1 - x0, y1 - y0
    n = max(abs(dx), abs(dy))
    if n == 0:
        return [[x0, y0]]
    return [[x0 - ((-2 * k * dx + n) // (2 * n)), y0 - ((-2 * k * dy + n) // (2 * n))]
            for k in range(n + 1)]


# --- code: one ICP iteration -------------------------------------------------------------------


def icp_step(P: Points, Q: Points) -> list[float]:
    theta, t, _ = scanmatch.icp_step(P, Q)
    return [theta, float(t[0]), float(t[1])]


def icp_inputs() -> Any:
    """``Q``: a reference scan of 3–12 points in [−20, 20]² m, at least 1 m apart. ``P``: a new
    scan of 2–12 of those points (any subset, any order) seen after a small motion (|θ| ≤ 0.3
    rad, |t| ≤ 1 m), optionally with 0.02 m noise. Draws whose matched pairs leave the angle
    ill-defined are rejected."""
    from hypothesis import strategies as st

    coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)

    def spread(pts: list[tuple[float, float]]) -> bool:
        a = np.asarray(pts)
        d = np.sqrt(np.sum((a[:, None] - a[None]) ** 2, axis=2)) + np.eye(len(a)) * 1e9
        return bool(d.min() >= 1.0)

    reference_scan = st.lists(st.tuples(coord, coord), min_size=3, max_size=12).filter(spread)

    def with_new_scan(q: list[tuple[float, float]]) -> Any:
        return st.tuples(
            st.just(q),
            st.lists(st.integers(0, len(q) - 1), min_size=2, max_size=12, unique=True),
            st.floats(-0.3, 0.3),
            st.floats(-1.0, 1.0),
            st.floats(-1.0, 1.0),
            st.sampled_from([0.0, 0.02]),
            st.integers(0, 2**31 - 1),
        )

    def make(args: tuple[Any, ...]) -> dict[str, Any]:
        q, index, theta, tx, ty, noise, seed = args
        qa = np.asarray(q, dtype=float)
        # p = R(θ)ᵀ (q − t): the new scan sees the same points from the moved pose
        p = (qa[index] - np.array([tx, ty])) @ scanmatch.rotation(theta)
        p = p + np.random.default_rng(seed).normal(0.0, noise, p.shape)
        return {"P": p.round(6).tolist(), "Q": qa.round(6).tolist()}

    def well_posed(d: dict[str, Any]) -> bool:
        p = np.asarray(d["P"])
        q = np.asarray(d["Q"])[scanmatch.nearest_neighbours(d["P"], d["Q"])]
        _, _, h = scanmatch.cross_covariance(p, q)
        size = float(np.sum((p - p.mean(axis=0)) ** 2))
        return size > 0.5 and math.hypot(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1]) > 1e-3 * size

    return reference_scan.flatmap(with_new_scan).map(make).filter(well_posed)


def mistake_icp_index_pairs(P: Points, Q: Points) -> list[float]:
    """``P[i]`` paired with ``Q[i]`` (as many as the shorter list): no nearest-neighbour search."""
    m = min(len(P), len(Q))
    return align_2d(list(P)[:m], list(Q)[:m])


def mistake_icp_reverse_search(P: Points, Q: Points) -> list[float]:
    """Each ``q`` paired with its nearest ``p`` (the search run the other way)."""
    pairs = scanmatch.nearest_neighbours(Q, P)
    return align_2d(np.asarray(P, dtype=float)[pairs], Q)


def mistake_icp_all_q_centroid(P: Points, Q: Points) -> list[float]:
    """Right pairs and angle, but ``t`` uses the centroid of the whole reference scan."""
    pairs = scanmatch.nearest_neighbours(P, Q)
    qa = np.asarray(Q, dtype=float)
    theta, _ = scanmatch.align_angle(P, qa[pairs])
    t = qa.mean(axis=0) - scanmatch.rotation(theta) @ np.asarray(P, dtype=float).mean(axis=0)
    return [theta, float(t[0]), float(t[1])]


# --- code: a beam's update of a 2-D grid ---------------------------------------------------------


def update_beam(grid: Sequence[Sequence[float]], x0: int, y0: int, x1: int, y1: int,
                l_occ: float, l_free: float) -> list[list[float]]:
    out = [list(map(float, row)) for row in grid]
    cells = raycast.bresenham(x0, y0, x1, y1)
    values = raycast.beam_update([out[y][x] for x, y in cells], l_occ, l_free)
    for (x, y), value in zip(cells, values, strict=True):
        out[y][x] = value
    return out


def beam_inputs() -> Any:
    """A grid of 1–12 rows × 1–12 columns of log-odds in [−5, 5] (lists), a start and an end
    cell inside it, ``l_occ`` in [0.1, 3] and ``l_free`` in [−3, −0.1]."""
    from hypothesis import strategies as st

    value = st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False)

    def for_size(size: tuple[int, int]) -> Any:
        h, w = size
        return st.fixed_dictionaries({
            "grid": st.lists(st.lists(value, min_size=w, max_size=w), min_size=h, max_size=h),
            "x0": st.integers(0, w - 1),
            "y0": st.integers(0, h - 1),
            "x1": st.integers(0, w - 1),
            "y1": st.integers(0, h - 1),
            "l_occ": st.floats(0.1, 3.0),
            "l_free": st.floats(-3.0, -0.1),
        })

    return st.tuples(st.integers(1, 12), st.integers(1, 12)).flatmap(for_size)


def mistake_beam_start_skipped(grid: Sequence[Sequence[float]], x0: int, y0: int, x1: int,
                               y1: int, l_occ: float, l_free: float) -> list[list[float]]:
    """The robot's own cell left out of the free cells."""
    out = update_beam(grid, x0, y0, x1, y1, l_occ, l_free)
    if (x0, y0) != (x1, y1):
        out[y0][x0] = float(grid[y0][x0])
    return out


def mistake_beam_hit_also_free(grid: Sequence[Sequence[float]], x0: int, y0: int, x1: int,
                               y1: int, l_occ: float, l_free: float) -> list[list[float]]:
    """The hit cell gets ``l_free`` as well as ``l_occ``."""
    out = update_beam(grid, x0, y0, x1, y1, l_occ, l_free)
    out[y1][x1] += l_free
    return out


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def _well_posed(p: np.ndarray, q: np.ndarray, spread: float) -> bool:
    """The best angle of the pairs ``p[i] ↔ q[i]`` is well defined."""
    _, _, h = scanmatch.cross_covariance(p, q)
    size = float(np.sum((p - p.mean(axis=0)) ** 2))
    return size > spread and math.hypot(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1]) > 1e-3 * size


def align_valid(P: Points, Q: Points) -> bool:
    """``align_2d``'s domain: two lists of the same number N ≥ 2 of 2-D points, those of ``P``
    not all in one place (spread over more than 0.5 m around their centroid), and a best
    angle that is well defined."""
    p, q = np.asarray(P, dtype=float), np.asarray(Q, dtype=float)
    if p.ndim != 2 or p.shape[1:] != (2,) or p.shape != q.shape or len(p) < 2:
        return False
    return _well_posed(p, q, 0.25 * len(p))


def icp_valid(P: Points, Q: Points) -> bool:
    """``icp_step``'s domain: N ≥ 2 points in ``P``, M ≥ 2 in ``Q``, no point of ``P`` almost
    (but not exactly) as near to two different points of ``Q`` (an exact tie follows the
    prompt's rule; a near one would hinge on rounding), and a well-defined best angle."""
    p, q = np.asarray(P, dtype=float), np.asarray(Q, dtype=float)
    if p.ndim != 2 or q.ndim != 2 or p.shape[1:] != (2,) or q.shape[1:] != (2,):
        return False
    if len(p) < 2 or len(q) < 2:
        return False
    d = np.sqrt(np.sum((p[:, None, :] - q[None, :, :]) ** 2, axis=2))
    for row in d:
        ranked = np.sort(np.unique(row))
        if len(ranked) > 1 and ranked[1] - ranked[0] < 1e-6:
            return False
    pairs = scanmatch.nearest_neighbours(p, q)
    return _well_posed(p, q[pairs], 0.5)


def beam_valid(grid: Sequence[Sequence[float]], x0: int, y0: int, x1: int, y1: int,
               l_occ: float, l_free: float) -> bool:
    """``update_beam``'s domain: a rectangular grid of 1–12 rows and columns, both cells inside
    it, ``l_occ`` > 0 and ``l_free`` < 0."""
    rows = len(grid)
    if not 1 <= rows <= 12:
        return False
    cols = len(grid[0])
    if not 1 <= cols <= 12 or any(len(row) != cols for row in grid):
        return False
    inside = all(0 <= x < cols for x in (x0, x1)) and all(0 <= y < rows for y in (y0, y1))
    return inside and l_occ > 0 and l_free < 0
