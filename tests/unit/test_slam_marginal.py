"""Property tests of :mod:`slamcourse.slam.marginal` against independent computations.

Schur complements against blocks of the dense inverse; marginal covariances against
``numpy.linalg.inv``; the conditional against the covariance-form Schur complement (the
duality of the chapter); symbolic fill against the numeric pattern of a Schur complement of a
random matrix with the graph's pattern.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import marginal as mg

FAST = settings(max_examples=80, deadline=None)


def spd(seed: int, n: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    a = rng.normal(size=(n, n))
    return a @ a.T + 0.5 * np.eye(n)


@st.composite
def systems(draw: st.DrawFn, full: bool = False) -> tuple[np.ndarray, np.ndarray, list[int]]:
    n = draw(st.integers(2, 9))
    seed = draw(st.integers(0, 2**32 - 1))
    perm = draw(st.permutations(list(range(n))))
    k = draw(st.integers(1, n if full else n - 1))
    b = np.random.default_rng(seed + 1).normal(size=n)
    return spd(seed, n), b, list(perm[:k])


@FAST
@given(systems())
def test_schur_complement_keeps_the_marginal(
    case: tuple[np.ndarray, np.ndarray, list[int]],
) -> None:
    h, b, keep = case
    h_new, b_new = mg.schur_complement(h, b, keep)
    sigma = np.linalg.inv(h)
    assert np.allclose(np.linalg.inv(h_new), sigma[np.ix_(keep, keep)], rtol=1e-8, atol=1e-10)
    assert np.allclose(np.linalg.solve(h_new, b_new), (sigma @ b)[keep], rtol=1e-8, atol=1e-10)


@FAST
@given(systems())
def test_marginalising_one_at_a_time_equals_all_at_once(
    case: tuple[np.ndarray, np.ndarray, list[int]],
) -> None:
    h, b, keep = case
    cur_h, cur_b, names = h, b, list(range(len(h)))
    for v in [i for i in range(len(h)) if i not in keep]:
        rest = [k for k, name in enumerate(names) if name != v]
        cur_h, cur_b = mg.schur_complement(cur_h, cur_b, rest)
        names = [names[k] for k in rest]
    order = [names.index(k) for k in keep]
    h_new, b_new = mg.schur_complement(h, b, keep)
    assert np.allclose(cur_h[np.ix_(order, order)], h_new, rtol=1e-9, atol=1e-9)
    assert np.allclose(cur_b[order], b_new, rtol=1e-9, atol=1e-9)


@FAST
@given(systems(full=True))
def test_marginal_and_conditional_covariances(
    case: tuple[np.ndarray, np.ndarray, list[int]],
) -> None:
    h, _, block = case
    sigma = np.linalg.inv(h)
    marginal = mg.marginal_covariance(h, block)
    assert np.allclose(marginal, sigma[np.ix_(block, block)], rtol=1e-9, atol=1e-12)
    rest = [i for i in range(len(h)) if i not in block]
    conditional = mg.conditional_covariance(h, block)
    # duality: conditioning is a Schur complement in covariance form
    expected = sigma[np.ix_(block, block)]
    if rest:
        s_am, s_mm = sigma[np.ix_(block, rest)], sigma[np.ix_(rest, rest)]
        expected = expected - s_am @ np.linalg.solve(s_mm, s_am.T)
    assert np.allclose(conditional, expected, rtol=1e-7, atol=1e-10)
    # the conditional is never larger than the marginal
    assert np.linalg.eigvalsh(marginal - conditional).min() > -1e-9


def test_scalar_example_by_hand() -> None:
    h = [[29.0, -25.0], [-25.0, 25.0]]
    assert mg.marginal_covariance(h, [1])[0, 0] == pytest.approx(29 / 100)
    assert mg.conditional_covariance(h, [1])[0, 0] == pytest.approx(1 / 25)
    h3 = [[29.0, -25.0, 0.0], [-25.0, 41.0, -16.0], [0.0, -16.0, 16.0]]
    h_new, _ = mg.schur_complement(h3, [0.0, 0.0, 0.0], [0, 2])
    assert h_new == pytest.approx(
        np.array([[29 - 625 / 41, -400 / 41], [-400 / 41, 16 - 256 / 41]])
    )


def _numeric_fill(
    n: int, edges: list[tuple[int, int]], removed: list[int], seed: int
) -> list[tuple[int, int]]:
    """Fill from the nonzeros of a real Schur complement of a random SPD matrix with
    the graph's pattern (generic values: no accidental cancellation)."""
    rng = np.random.default_rng(seed)
    h = np.zeros((n, n))
    for i, j in edges:
        h[i, j] = h[j, i] = rng.uniform(0.1, 1.0) * rng.choice([-1, 1])
    h += np.diag(np.abs(h).sum(axis=1) + 1.0)  # diagonally dominant: positive definite
    keep = [i for i in range(n) if i not in removed]
    h_new, _ = mg.schur_complement(h, np.zeros(n), keep)
    before = {(min(i, j), max(i, j)) for i, j in edges if i != j}
    after = {
        (keep[r], keep[c])
        for r, c in itertools.combinations(range(len(keep)), 2)
        if abs(h_new[r, c]) > 1e-12
    }
    return sorted(after - before)


@FAST
@given(st.integers(2, 10), st.integers(0, 2**32 - 1), st.data())
def test_symbolic_fill_matches_a_numeric_schur_complement(
    n: int, seed: int, data: st.DataObject
) -> None:
    pairs = list(itertools.combinations(range(n), 2))
    edges = data.draw(st.lists(st.sampled_from(pairs), max_size=2 * n, unique=True))
    removed = data.draw(st.lists(st.integers(0, n - 1), min_size=1, max_size=n - 1, unique=True))
    fill = _numeric_fill(n, edges, removed, seed)
    assert mg.marginal_fill(n, edges, removed) == fill
    assert mg.marginal_fill(n, edges, removed[::-1]) == fill


@FAST
@given(st.integers(2, 10), st.integers(0, 2**32 - 1), st.data())
def test_markov_blanket_is_where_a_numeric_schur_complement_changes(
    n: int, seed: int, data: st.DataObject
) -> None:
    """The blanket against the rows of a real Schur complement that differ from ``H_aa`` (the
    prior's variables), for random graphs; pairs and an m×2 array give the same."""
    pairs = list(itertools.combinations(range(n), 2))
    edges = data.draw(st.lists(st.sampled_from(pairs), max_size=2 * n, unique=True))
    edges = [(j, i) if data.draw(st.booleans()) else (i, j) for i, j in edges]  # either way
    removed = data.draw(st.lists(st.integers(0, n - 1), min_size=1, max_size=n - 1, unique=True))
    rng = np.random.default_rng(seed)
    h = np.zeros((n, n))
    for i, j in edges:
        h[i, j] = h[j, i] = rng.uniform(0.1, 1.0) * rng.choice([-1, 1])
    h += np.diag(np.abs(h).sum(axis=1) + 1.0)
    keep = [i for i in range(n) if i not in removed]
    h_new, _ = mg.schur_complement(h, np.zeros(n), keep)
    changed = np.abs(h_new - h[np.ix_(keep, keep)]).max(axis=1) > 1e-12
    expected = [keep[r] for r in np.flatnonzero(changed)]
    assert mg.markov_blanket(n, edges, removed) == expected
    array = np.array(edges, dtype=np.int64).reshape(-1, 2)
    assert mg.markov_blanket(n, array, iter(removed)) == expected


def test_markov_blanket_of_one_variable_is_its_neighbours() -> None:
    edges = [(0, 1), (0, 2), (2, 3), (3, 4), (1, 5)]
    assert mg.markov_blanket(6, edges, [0]) == [1, 2]
    # through a removed neighbour: 0 and 2 removed, so 3 joins the blanket
    assert mg.markov_blanket(6, edges, [0, 2]) == [1, 3]
    assert mg.blocks([1, 0]) == [3, 4, 5, 0, 1, 2]
