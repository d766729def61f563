"""Properties of the reference library of chapters 17–18: orderings, scan matching, ray casting."""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import orderings as so


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
