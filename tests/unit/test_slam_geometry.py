"""Properties of the reference library of chapters 17–18: orderings, scan matching, ray casting."""

from __future__ import annotations

from fractions import Fraction
from itertools import pairwise

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import orderings as so
from slamcourse.slam import raycast as rc
from slamcourse.slam import scanmatch as sm


@st.composite
def graphs(draw: st.DrawFn, max_n: int = 10) -> tuple[int, list[tuple[int, int]]]:
    n = draw(st.integers(1, max_n))
    if n == 1:
        return 1, []
    pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
    return n, draw(st.lists(pair, max_size=2 * n))


def _spd(n: int, edges: list[tuple[int, int]]) -> np.ndarray:
    h = np.eye(n)
    for i, j in so.unique_edges(edges):
        h[i, j] = h[j, i] = -1.0
        h[i, i] += 1.0
        h[j, j] += 1.0
    return h


# --- orderings ---------------------------------------------------------------------------------


@settings(max_examples=40, deadline=None)
@given(graphs(), st.randoms(use_true_random=False))
def test_symbolic_nonzeros_match_a_numeric_cholesky(
    graph: tuple[int, list[tuple[int, int]]], rnd: object
) -> None:
    n, edges = graph
    order = list(range(n))
    rnd.shuffle(order)  # type: ignore[attr-defined]
    lower = np.linalg.cholesky(_spd(n, edges)[np.ix_(order, order)])
    assert so.factor_nonzeros(n, edges, order) == int(np.count_nonzero(np.abs(lower) > 1e-12))
    assert sum(so.column_counts(n, edges, order)) == so.factor_nonzeros(n, edges, order) - n


@settings(max_examples=40, deadline=None)
@given(graphs())
def test_min_degree_is_a_permutation_and_beats_the_worst_case(
    graph: tuple[int, list[tuple[int, int]]],
) -> None:
    n, edges = graph
    order = so.min_degree_order(n, edges)
    assert sorted(order) == list(range(n))
    # never worse than eliminating everything into one clique
    assert so.factor_nonzeros(n, edges, order) <= n * (n + 1) // 2


@settings(max_examples=40, deadline=None)
@given(st.integers(2, 40), st.randoms(use_true_random=False))
def test_min_degree_makes_no_fill_on_trees(n: int, rnd: object) -> None:
    """A tree (here a random one: each vertex joined to an earlier one) has a fill-free order."""
    edges = [(v, rnd.randrange(v)) for v in range(1, n)]  # type: ignore[attr-defined]
    assert so.fill_count(n, edges, so.min_degree_order(n, edges)) == 0
    assert so.fill_count(n, so.chain(n), list(range(n))) == 0


def test_closed_forms_on_synthetic_graphs() -> None:
    assert so.fill_count(7, so.star(6), list(range(7))) == 15
    assert so.fill_count(7, so.star(6), [*range(1, 7), 0]) == 0
    cycle = [*so.chain(8), (0, 7)]
    for start in range(8):
        order = [*range(start, 8), *range(start)]
        assert so.fill_count(8, cycle, order) == 5  # a cycle of m costs m − 3, whatever the order
    # a k×k grid in row order: column v of L fills the band up to v + k (after the first row,
    # which only reaches its own row-neighbour chain plus the cell below: v + 2 entries)
    k = 4
    banded = sum(min(v + 2, k, k * k - 1 - v) for v in range(k * k))
    assert so.factor_nonzeros(k * k, so.grid(k, k), list(range(k * k))) == k * k + banded


@settings(max_examples=30, deadline=None)
@given(graphs(), st.randoms(use_true_random=False))
def test_permuted_solve_equals_the_unpermuted_one(
    graph: tuple[int, list[tuple[int, int]]], rnd: object
) -> None:
    n, edges = graph
    h = _spd(n, edges)
    b = np.arange(1.0, n + 1.0)
    order = so.min_degree_order(n, edges)
    lower = np.linalg.cholesky(h[np.ix_(order, order)])
    y = np.linalg.solve(lower, b[order])
    x_perm = np.linalg.solve(lower.T, y)
    x = np.empty(n)
    x[order] = x_perm
    np.testing.assert_allclose(x, np.linalg.solve(h, b), rtol=1e-9, atol=1e-12)


def test_g2o_pose_edges_reads_vertices_and_edges() -> None:
    text = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n\nEDGE_SE2 0 1 1 0 0 1 0 0 1 0 1\nFIX 0\n"
    assert so.g2o_pose_edges(text) == (2, [(0, 1)])


# --- scan matching -----------------------------------------------------------------------------

coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
clouds = st.lists(st.tuples(coord, coord), min_size=3, max_size=12).filter(
    lambda pts: float(np.sum((np.asarray(pts) - np.mean(pts, axis=0)) ** 2)) > 1.0
)
angles = st.floats(-3.1, 3.1)
shifts = st.tuples(st.floats(-5.0, 5.0), st.floats(-5.0, 5.0))


@settings(max_examples=60, deadline=None)
@given(clouds, angles, shifts, st.randoms(use_true_random=False))
def test_alignment_recovers_a_rigid_motion_in_any_point_order(
    pts: list[tuple[float, float]], theta: float, t: tuple[float, float], rnd: object
) -> None:
    p = np.asarray(pts)
    q = p @ sm.rotation(theta).T + np.asarray(t)
    got, t_got = sm.align_angle(p, q)
    assert abs(np.angle(np.exp(1j * (got - theta)))) < 1e-7
    np.testing.assert_allclose(t_got, t, atol=1e-6)
    r, t_svd = sm.align_svd(p, q)
    np.testing.assert_allclose(r, sm.rotation(theta), atol=1e-7)
    np.testing.assert_allclose(t_svd, t, atol=1e-6)
    index = list(range(len(p)))
    rnd.shuffle(index)  # type: ignore[attr-defined]
    again, _ = sm.align_angle(p[index], q[index])
    assert abs(np.angle(np.exp(1j * (again - got)))) < 1e-9


@settings(max_examples=60, deadline=None)
@given(clouds, clouds)
def test_alignment_is_a_rotation_and_a_least_squares_minimum(
    a: list[tuple[float, float]], b: list[tuple[float, float]]
) -> None:
    m = min(len(a), len(b))
    p, q = np.asarray(a[:m]), np.asarray(b[:m])
    r, t = sm.align_svd(p, q)
    assert np.linalg.det(r) == pytest.approx(1.0)
    theta, t2 = sm.align_angle(p, q)
    best = sm.sum_squared_error(p, q, theta, t2)
    # the SVD rotation and the closed form agree (up to ties of a degenerate cost)
    assert sm.sum_squared_error(p, q, float(np.arctan2(r[1, 0], r[0, 0])), t) == pytest.approx(
        best, rel=1e-9, abs=1e-9
    )
    for d_theta in (-0.01, 0.01):
        assert best <= sm.sum_squared_error(p, q, theta + d_theta, t2) + 1e-9
    for d_t in ((0.01, 0.0), (0.0, -0.01)):
        assert best <= sm.sum_squared_error(p, q, theta, t2 + np.asarray(d_t)) + 1e-9


@settings(max_examples=40, deadline=None)
@given(clouds, st.floats(-0.3, 0.3), shifts)
def test_an_icp_step_never_raises_the_nearest_neighbour_cost(
    pts: list[tuple[float, float]], theta: float, t: tuple[float, float]
) -> None:
    q = np.asarray(pts)
    p = (q - np.asarray(t) / 10) @ sm.rotation(theta)
    before = float(np.sum((p - q[sm.nearest_neighbours(p, q)]) ** 2))
    step, t_step, pairs = sm.icp_step(p, q)
    after = sm.sum_squared_error(p, q[pairs], step, t_step)
    assert after <= before + 1e-9


# --- ray casting -------------------------------------------------------------------------------

cells = st.integers(-60, 60)


@settings(max_examples=200, deadline=None)
@given(cells, cells, cells, cells)
def test_bresenham_is_exact_connected_and_symmetric(x0: int, y0: int, x1: int, y1: int) -> None:
    line = rc.bresenham(x0, y0, x1, y1)
    n = max(abs(x1 - x0), abs(y1 - y0))
    assert len(line) == n + 1 and line[0] == (x0, y0) and line[-1] == (x1, y1)
    assert all(max(abs(a[0] - b[0]), abs(a[1] - b[1])) == 1 for a, b in pairwise(line))
    assert rc.bresenham(x1, y1, x0, y0) == line[::-1]
    for k, (x, y) in enumerate(line):
        # each cell is within half a cell of the exact line, measured along the minor axis
        if n:
            ex, ey = (
                Fraction(x0) + Fraction(k * (x1 - x0), n),
                Fraction(y0) + Fraction(k * (y1 - y0), n),
            )
            assert abs(x - ex) <= Fraction(1, 2) and abs(y - ey) <= Fraction(1, 2)


def test_bresenham_edge_cases() -> None:
    assert rc.bresenham(3, -2, 3, -2) == [(3, -2)]
    assert rc.bresenham(0, 0, 4, 1) == [(0, 0), (1, 0), (2, 1), (3, 1), (4, 1)]  # 0.5 rounds up
    assert rc.bresenham(0, 0, 4, -1)[2] == (2, 0)  # −0.5 rounds up too
    assert rc.bresenham(0, 0, 0, -3) == [(0, 0), (0, -1), (0, -2), (0, -3)]
    assert rc.bresenham(-1, 2, 2, 2) == [(-1, 2), (0, 2), (1, 2), (2, 2)]


@settings(max_examples=60, deadline=None)
@given(
    st.lists(st.floats(-5, 5), min_size=1, max_size=10),
    st.floats(0.1, 3.0),
    st.floats(-3.0, -0.1),
)
def test_beam_update_marks_free_then_occupied_and_commutes(
    row: list[float], l_occ: float, l_free: float
) -> None:
    out = rc.beam_update(row, l_occ, l_free)
    assert out[-1] == pytest.approx(row[-1] + l_occ)
    assert out[:-1] == pytest.approx([v + l_free for v in row[:-1]])
    twice = rc.beam_update(rc.beam_update(row, l_occ, l_free, hit=False), l_occ, l_free)
    other = rc.beam_update(rc.beam_update(row, l_occ, l_free), l_occ, l_free, hit=False)
    assert twice == pytest.approx(other)
    assert rc.log_odds_after_hits(0.0, l_occ, 50, l_max=3.5) <= 3.5
