"""Properties of the course's reference mathematics for chapters 3–5 (``slamcourse.slam``).

Each property is checked against something computed another way: scipy's χ² distribution, an
explicit Cholesky whitening, a plain Python sum, the numeric Cholesky factor's nonzeros, the
normal equations of the cost the information form minimises.
"""

from __future__ import annotations

import math
import random

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy import stats

from slamcourse.slam import association, drift, graph

finite = st.floats(-10, 10, allow_nan=False, allow_infinity=False)


@st.composite
def innovation_and_covariance(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray]:
    """An innovation ν (m,) and a well-conditioned SPD covariance S (m × m), m = 1…3."""
    m = draw(st.integers(1, 3))
    nu = np.array(draw(st.lists(finite, min_size=m, max_size=m)))
    a = np.array(draw(st.lists(finite, min_size=m * m, max_size=m * m))).reshape(m, m)
    s = a @ a.T + draw(st.floats(0.1, 5)) * np.eye(m)
    return nu, s


# --- association -----------------------------------------------------------------------------


@settings(max_examples=40)
@given(innovation_and_covariance())
def test_mahalanobis_is_nonnegative_and_equals_whitened_length(
    case: tuple[np.ndarray, np.ndarray],
) -> None:
    nu, s = case
    d2 = association.mahalanobis_squared(nu, s)
    whitened = np.linalg.solve(np.linalg.cholesky(s), nu)  # L⁻¹ν, with S = L Lᵀ
    assert d2 >= 0
    assert d2 == pytest.approx(float(whitened @ whitened), rel=1e-9, abs=1e-9)


@settings(max_examples=40)
@given(innovation_and_covariance(), st.floats(0.01, 100))
def test_mahalanobis_is_invariant_under_a_change_of_units(
    case: tuple[np.ndarray, np.ndarray], c: float
) -> None:
    # measuring ν in other units (ν → cν) scales S by c²: the distance must not change
    nu, s = case
    assert association.mahalanobis_squared(c * nu, c * c * s) == pytest.approx(
        association.mahalanobis_squared(nu, s), rel=1e-8, abs=1e-10
    )


@given(finite, st.floats(0.001, 10), finite, st.floats(0.001, 10))
def test_mahalanobis_of_a_diagonal_covariance_is_a_sum_of_ratios(
    nu0: float, s00: float, nu1: float, s11: float
) -> None:
    d2 = association.mahalanobis_squared([nu0, nu1], np.diag([s00, s11]))
    assert d2 == pytest.approx(nu0**2 / s00 + nu1**2 / s11, rel=1e-12, abs=1e-12)
    assert association.mahalanobis_squared(nu0, s00) == pytest.approx(nu0**2 / s00, rel=1e-12)


def test_mahalanobis_rejects_a_covariance_of_the_wrong_shape() -> None:
    with pytest.raises(ValueError, match="shape"):
        association.mahalanobis_squared([1.0, 2.0], np.eye(3))


@settings(max_examples=40)
@given(st.floats(0, 60), st.integers(1, 8))
def test_chi2_cdf_matches_scipy(x: float, dof: int) -> None:
    assert association.chi2_cdf(x, dof) == pytest.approx(float(stats.chi2.cdf(x, dof)), abs=1e-12)
    assert association.chi2_tail(x, dof) == pytest.approx(float(stats.chi2.sf(x, dof)), abs=1e-12)


@settings(max_examples=40)
@given(st.floats(0.01, 0.999), st.integers(1, 8))
def test_chi2_quantile_matches_scipy_and_inverts_the_cdf(confidence: float, dof: int) -> None:
    x = association.chi2_quantile(confidence, dof)
    assert x == pytest.approx(float(stats.chi2.ppf(confidence, dof)), rel=1e-9)
    assert association.chi2_cdf(x, dof) == pytest.approx(confidence, abs=1e-9)


def test_the_textbook_gates() -> None:
    assert association.chi2_quantile(0.95, 1) == pytest.approx(1.959964**2, rel=1e-6)
    assert association.chi2_quantile(0.95, 2) == pytest.approx(-2 * math.log(0.05), rel=1e-12)
    assert association.chi2_cdf(1.0, 1) == pytest.approx(math.erf(1 / math.sqrt(2)), rel=1e-12)


@pytest.mark.parametrize("bad", [0.0, 1.0, -0.5, 1.5])
def test_chi2_quantile_rejects_a_confidence_outside_0_1(bad: float) -> None:
    with pytest.raises(ValueError, match="confidence"):
        association.chi2_quantile(bad, 2)


@settings(max_examples=40)
@given(st.lists(st.floats(0, 30), max_size=6), st.integers(1, 3), st.floats(0.5, 0.999))
def test_gate_decision_is_the_nearest_candidate_inside_the_gate(
    d2s: list[float], dof: int, confidence: float
) -> None:
    threshold = float(stats.chi2.ppf(confidence, dof))
    assume(all(abs(d - threshold) > 1e-6 for d in d2s))
    chosen = association.gate_decision(d2s, dof, confidence)
    inside = [d for d in d2s if d < threshold]
    if inside:
        assert d2s[chosen] == min(inside)
    else:
        assert chosen == -1


# --- drift -----------------------------------------------------------------------------------


@given(st.floats(0.001, 1), st.integers(0, 500), st.integers(0, 500))
def test_random_walk_variances_add(sigma: float, a: int, b: int) -> None:
    total = drift.random_walk_sigma(sigma, a + b) ** 2
    parts = drift.random_walk_sigma(sigma, a) ** 2 + drift.random_walk_sigma(sigma, b) ** 2
    assert total == pytest.approx(parts, rel=1e-12, abs=1e-15)


@given(st.floats(0.05, 2), st.floats(0.0005, 0.05), st.integers(0, 400))
def test_lateral_drift_is_the_sum_of_sideways_steps(
    step_length: float, heading_rate: float, steps: int
) -> None:
    plain = sum(step_length * math.sin(heading_rate * k) for k in range(1, steps + 1))
    assert drift.lateral_drift(step_length, heading_rate, steps) == pytest.approx(
        plain, rel=1e-9, abs=1e-9
    )
    # and never more than the small-angle sum, since sin x ≤ x for x ≥ 0
    assert drift.lateral_drift(step_length, heading_rate, steps) <= (
        step_length * heading_rate * steps * (steps + 1) / 2 + 1e-9
    )


def test_dead_reckoning_of_a_square_closes() -> None:
    headings = np.repeat([0, math.pi / 2, math.pi, 3 * math.pi / 2], 10)
    path = drift.dead_reckoning(np.full(40, 1.02), headings)
    assert path.shape == (41, 2)
    assert np.allclose(path[-1], 0, atol=1e-9)
    assert np.allclose(path[20], [10.2, 10.2])


@settings(max_examples=40)
@given(
    st.lists(st.floats(0.1, 10), min_size=1, max_size=10),
    st.floats(-5, 5),
    st.floats(0.01, 10),
)
def test_loop_closure_correction_is_the_graph_solution(
    variances: list[float], closure_error: float, loop_variance: float
) -> None:
    # the same loop as a pose graph: zero odometry, a loop closure measuring closure_error, a
    # stiff prior holding x_0 at 0. Dead reckoning is all zeros, so μ is the correction itself.
    n = len(variances)
    edges = [(k, k + 1, 0.0, 1 / v) for k, v in enumerate(variances)]
    edges.append((0, n, closure_error, 1 / loop_variance))
    omega, xi = graph.information_form(n + 1, edges, [(0, 0.0, 1e9)])
    expected = graph.solve(omega, xi)
    got = drift.loop_closure_correction(variances, closure_error, loop_variance)
    assert got == pytest.approx(expected, abs=1e-6)


@given(st.integers(1, 50), st.floats(-5, 5))
def test_an_exact_loop_closure_moves_pose_k_by_k_over_n(n: int, e: float) -> None:
    got = drift.loop_closure_correction([1.0] * n, e)
    assert got == pytest.approx([e * k / n for k in range(n + 1)], abs=1e-12)


# --- graph -----------------------------------------------------------------------------------


@st.composite
def pose_graphs(draw: st.DrawFn) -> tuple[int, list[graph.Edge]]:
    n = draw(st.integers(2, 8))
    pair = st.tuples(st.integers(0, n - 1), st.integers(0, n - 1)).filter(lambda p: p[0] != p[1])
    edges = draw(
        st.lists(
            st.builds(lambda p, z, w: (p[0], p[1], z, w), pair, finite, st.floats(0.1, 10)),
            max_size=12,
        )
    )
    return n, edges


@settings(max_examples=40)
@given(pose_graphs())
def test_omega_is_symmetric_psd_and_its_rows_sum_to_zero(
    case: tuple[int, list[graph.Edge]],
) -> None:
    n, edges = case
    omega, xi = graph.information_form(n, edges)
    assert np.array_equal(omega, omega.T)
    assert np.linalg.eigvalsh(omega).min() >= -1e-9 * max(1.0, np.abs(omega).max())
    assert np.allclose(omega.sum(axis=1), 0)  # edges alone fix only differences
    assert xi.sum() == pytest.approx(0, abs=1e-9)


@settings(max_examples=40)
@given(pose_graphs(), st.floats(0.5, 20), finite)
def test_the_solution_satisfies_the_system_and_minimises_the_cost(
    case: tuple[int, list[graph.Edge]], prior: float, value: float
) -> None:
    n, edges = case
    # a chain keeps the graph connected, so the prior on x_0 makes Ω positive definite
    edges = [*graph.chain_edges(n, 1.0, 1.0), *edges]
    omega, xi = graph.information_form(n, edges, [(0, value, prior)])
    mu = graph.solve(omega, xi)
    assert omega @ mu == pytest.approx(xi, abs=1e-7 * max(1.0, np.abs(xi).max()))

    def cost(x: np.ndarray) -> float:
        terms = [w * (x[j] - x[i] - z) ** 2 for i, j, z, w in edges]
        return float(sum(terms) + prior * (x[0] - value) ** 2)

    rng = np.random.default_rng(0)
    for _ in range(5):
        assert cost(mu) <= cost(mu + rng.normal(scale=0.1, size=n)) + 1e-9


@given(st.integers(2, 40))
def test_a_chain_is_tridiagonal_with_3n_minus_2_nonzeros(n: int) -> None:
    omega = graph.information_matrix(n, graph.chain_edges(n), [(0, 0.0, 1.0)])
    i, j = np.nonzero(omega)
    assert np.all(np.abs(i - j) <= 1)
    assert len(i) == 3 * n - 2 == graph.nonzero_blocks(n, [(k, k + 1) for k in range(n - 1)])


@settings(max_examples=40)
@given(pose_graphs())
def test_nonzero_blocks_counts_the_nonzeros_of_omega(case: tuple[int, list[graph.Edge]]) -> None:
    n, edges = case
    omega = graph.information_matrix(n, edges, [(k, 0.0, 1.0) for k in range(n)])
    assert graph.nonzero_blocks(n, [(i, j) for i, j, _, _ in edges]) == np.count_nonzero(omega)


@settings(max_examples=40)
@given(pose_graphs(), st.randoms(use_true_random=False))
def test_symbolic_fill_in_matches_the_numeric_cholesky_factor(
    case: tuple[int, list[graph.Edge]], rnd: random.Random
) -> None:
    n, edges = case
    omega = graph.information_matrix(n, edges, [(k, 0.0, 1.0) for k in range(n)])
    order = list(range(n))
    rnd.shuffle(order)
    permuted = omega[np.ix_(order, order)]  # eliminating in `order` = factorising this
    factor = np.linalg.cholesky(permuted)
    assert graph.cholesky_nonzeros(omega != 0, order) == np.count_nonzero(np.abs(factor) > 1e-12)


def test_a_loop_closure_fills_the_factor_of_a_chain() -> None:
    n = 1000
    pattern = graph.information_matrix(n, graph.chain_edges(n)) != 0
    assert graph.cholesky_nonzeros(pattern) == 2 * n - 1
    pattern[0, n - 1] = pattern[n - 1, 0] = True
    assert graph.cholesky_nonzeros(pattern) == 3 * n - 3


def test_edges_must_join_two_poses_and_orders_must_be_permutations() -> None:
    with pytest.raises(ValueError, match="two different poses"):
        graph.information_form(2, [(1, 1, 0.0, 1.0)])
    with pytest.raises(ValueError, match="permutation"):
        graph.cholesky_nonzeros(np.eye(3, dtype=bool), [0, 0, 1])
