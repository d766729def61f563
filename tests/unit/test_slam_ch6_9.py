"""Properties of the course library for chapters 6–9 (:mod:`slamcourse.slam`)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from slamcourse.slam import capstone, factor, occupancy, vision

finite = {"allow_nan": False, "allow_infinity": False}
coord = st.floats(-3.0, 3.0, **finite)
angle = st.floats(-math.pi, math.pi, **finite)
translation = st.tuples(coord, coord, coord).filter(lambda t: math.hypot(*t) >= 0.1)
prob = st.floats(0.02, 0.98, **finite)


def rotation(yaw: float, pitch: float) -> np.ndarray:
    return vision.rotation_z(yaw) @ vision.rotation_y(pitch)


# --- vision ---------------------------------------------------------------------------------


@given(translation, angle, angle)
def test_essential_matrix_has_two_equal_singular_values_and_a_zero(
    t: tuple[float, float, float], yaw: float, pitch: float
) -> None:
    E = vision.essential_from_pose(t, rotation(yaw, pitch))
    s = vision.singular_values(E)
    norm = math.hypot(*t)
    assert s == pytest.approx([norm, norm, 0.0], abs=1e-9 * max(1.0, norm))
    assert vision.is_essential(E)


@given(translation, angle, angle)
def test_skew_is_the_cross_product(t: tuple[float, float, float], yaw: float, pitch: float) -> None:
    v = rotation(yaw, pitch) @ np.array([1.0, 2.0, 3.0])
    assert vision.skew(t) @ v == pytest.approx(np.cross(t, v), abs=1e-9)


@settings(max_examples=60)
@given(
    translation,
    angle,
    st.floats(-0.5, 0.5, **finite),
    st.tuples(coord, coord, st.floats(2.0, 20.0, **finite)),
)
def test_true_correspondences_satisfy_the_epipolar_constraint(
    t: tuple[float, float, float], yaw: float, pitch: float, X: tuple[float, float, float]
) -> None:
    R = rotation(yaw, pitch)
    X1 = np.array(X)
    X2 = R @ X1 + np.array(t)  # the point in the second camera's frame
    assume(X2[2] >= 0.5)  # behind or too close to the second camera: no image
    x, x2 = X1 / X1[2], X2 / X2[2]
    E = vision.essential_from_pose(t, R)
    assert vision.epipolar_residual(E, x, x2) == pytest.approx(0.0, abs=1e-9)


@settings(max_examples=60)
@given(
    translation,
    angle,
    st.floats(300.0, 900.0, **finite),
    st.floats(200.0, 700.0, **finite),
    st.floats(150.0, 500.0, **finite),
    st.tuples(coord, coord, st.floats(2.0, 20.0, **finite)),
)
def test_fundamental_matrix_holds_in_pixels_and_maps_back_to_e(
    t: tuple[float, float, float],
    yaw: float,
    f: float,
    cx: float,
    cy: float,
    X: tuple[float, float, float],
) -> None:
    R = vision.rotation_z(yaw)
    K = vision.intrinsics(f, cx, cy)
    E = vision.essential_from_pose(t, R)
    F = vision.fundamental_from_essential(E, K)
    X1 = np.array(X)
    X2 = R @ X1 + np.array(t)
    assume(X2[2] >= 0.5)
    p, p2 = K @ (X1 / X1[2]), K @ (X2 / X2[2])
    assert float(p2 @ F @ p) == pytest.approx(0.0, abs=1e-8)
    assert vision.essential_from_fundamental(F, K) == pytest.approx(E, abs=1e-9)
    assert vision.singular_values(F)[2] == pytest.approx(0.0, abs=1e-12)  # rank 2


def test_a_rank_two_matrix_with_unequal_singular_values_is_not_essential() -> None:
    M = [[0.0, -1.0, 0.0], [1.0, 0.0, -0.5], [0.0, 0.3, 0.0]]
    assert np.linalg.matrix_rank(M) == 2
    assert not vision.is_essential(M)


@given(st.floats(0.3, 0.95, **finite), st.integers(1, 8), st.sampled_from([0.9, 0.95, 0.99]))
def test_ransac_count_is_the_smallest_that_reaches_the_confidence(
    w: float, s: int, p: float
) -> None:
    n = vision.ransac_iterations(w, s, p)
    assert vision.all_samples_fail(w, s, n) <= (1 - p) * (1 + 1e-12)
    if n > 1:
        assert vision.all_samples_fail(w, s, n - 1) > 1 - p


def test_ransac_counts_of_the_lesson() -> None:
    assert [vision.ransac_iterations(w, s, 0.99) for w, s in [(0.5, 5), (0.8, 5), (0.5, 8)]] == [
        146,
        12,
        1177,
    ]


@pytest.mark.parametrize("p", [0.9, 0.95, 0.99])
def test_chi2_quantiles_invert_the_cdf(p: float) -> None:
    # CDFs in closed form: χ²₁ is P(Z² ≤ x) = erf(√(x/2)); χ²₂ is 1 − e^{−x/2}
    assert math.erf(math.sqrt(vision.chi2_quantile(p, 1) / 2)) == pytest.approx(p, rel=1e-12)
    assert 1 - math.exp(-vision.chi2_quantile(p, 2) / 2) == pytest.approx(p, rel=1e-12)


def test_sampson_threshold_scales_with_the_noise_variance() -> None:
    assert vision.sampson_threshold(1.0, 0.95) == pytest.approx(3.8414588, rel=1e-7)
    assert vision.sampson_threshold(2.0, 0.95) == pytest.approx(4 * 3.8414588, rel=1e-7)


# --- factor graphs --------------------------------------------------------------------------


@given(st.integers(1, 40))
def test_a_chain_eliminated_end_to_end_has_no_fill_in(n: int) -> None:
    assert factor.fill_in(n, factor.chain(n), list(range(n))) == 0
    assert factor.fill_in(n, factor.chain(n), list(range(n - 1, -1, -1))) == 0


@given(st.integers(3, 30), st.data())
def test_eliminating_a_middle_node_links_its_neighbours(n: int, data: st.DataObject) -> None:
    k = data.draw(st.integers(1, n - 2))
    order = [k] + [v for v in range(n) if v != k]
    assert factor.eliminate(n, factor.chain(n), order)[0] == (k - 1, k + 1)


@given(st.integers(1, 20))
def test_star_fill_in_depends_on_the_order(leaves: int) -> None:
    centre_first = list(range(leaves + 1))
    leaves_first = [*range(1, leaves + 1), 0]
    assert factor.fill_in(leaves + 1, factor.star(leaves), centre_first) == math.comb(leaves, 2)
    assert factor.fill_in(leaves + 1, factor.star(leaves), leaves_first) == 0


@given(st.integers(1, 7), st.data())
def test_fill_in_ignores_edge_orientation_and_stays_below_the_clique(
    n: int, data: st.DataObject
) -> None:
    pairs = [(a, b) for a in range(n) for b in range(a + 1, n)]
    edges = data.draw(st.lists(st.sampled_from(pairs), unique=True)) if pairs else []
    order = data.draw(st.permutations(list(range(n))))
    created = factor.fill_in(n, edges, order)
    assert created == factor.fill_in(n, [(b, a) for a, b in edges], order)
    assert 0 <= created <= len(pairs) - len(edges)


def test_factor_counts_of_the_lesson() -> None:
    assert factor.factor_and_variable_counts(5, 3, 2) == (11, 8)
    assert factor.constraint_dof(100, 200) == 700
    assert factor.unknown_dof(100, 50) == 400


# --- occupancy ------------------------------------------------------------------------------


@given(st.lists(prob, max_size=8), st.data())
def test_log_odds_updates_commute(readings: list[float], data: st.DataObject) -> None:
    shuffled = data.draw(st.permutations(readings))
    assert occupancy.fuse(shuffled) == pytest.approx(occupancy.fuse(readings), abs=1e-9)


@given(prob)
def test_probability_inverts_log_odds(p: float) -> None:
    assert occupancy.probability(occupancy.log_odds(p)) == pytest.approx(p, rel=1e-12)
    assert occupancy.log_odds(1 - p) == pytest.approx(-occupancy.log_odds(p), abs=1e-12)


@given(st.lists(prob, max_size=30), st.floats(0.5, 10.0, **finite))
def test_clamped_log_odds_stay_in_range(readings: list[float], bound: float) -> None:
    l_cell = occupancy.fuse_clamped(readings, -bound, bound)
    assert -bound <= l_cell <= bound


@given(st.floats(0.01, 200.0, **finite), st.floats(0.02, 0.48, **finite))
def test_readings_to_flip_is_the_first_count_below_zero(l0: float, p_free: float) -> None:
    n = occupancy.readings_to_flip(l0, p_free)
    assert occupancy.fuse([p_free] * n, l0) < 0
    assert occupancy.fuse([p_free] * (n - 1), l0) >= -1e-9


def test_occupancy_figures_of_the_lesson() -> None:
    l_cell = occupancy.fuse([0.9, 0.3])
    assert l_cell == pytest.approx(1.350, abs=5e-4)
    assert occupancy.probability(l_cell) == pytest.approx(0.794, abs=5e-4)
    assert occupancy.readings_to_reach(l_cell, 0.0, 0.3) == 2  # 1.59 more, not 2.6
    assert occupancy.readings_to_reach(0.0, occupancy.log_odds(0.95), 0.7) == 4
    assert occupancy.readings_to_flip(occupancy.fuse([0.9] * 50), 0.3) == 130
    assert occupancy.readings_to_flip(5.0, 0.3) == 6
    assert occupancy.grid_cells(100, 0.05) == 4_000_000


# --- capstone -------------------------------------------------------------------------------


@given(st.floats(1e-4, 1.0, **finite), st.integers(1, 10_000))
def test_random_walk_adds_variances(sigma: float, k: int) -> None:
    assert capstone.random_walk(sigma, k) ** 2 == pytest.approx(k * sigma**2, rel=1e-9)


def test_capstone_figures() -> None:
    assert capstone.graph_variables(5, 10, 10, 2) == (300, 600)
    assert capstone.graph_dof(300, 600) == 2100
    pos, theta = capstone.odometry_step_sigma(0.5, 0.01, 0.5)
    assert (pos, theta) == pytest.approx((0.005, 0.25 * math.pi / 180))
    assert capstone.scan_readings(360, 1, 0.3) == pytest.approx(108)
    assert capstone.grid_bytes(50, 0.02) == 6_250_000
    assert capstone.graph_bytes(300, 600) == (2100 + 3 * (300 * 9 + 600 * 4)) * 8
    assert capstone.frame_headroom(10, [0.5, 15, 5, 10, 30, 20]) == pytest.approx((80.5, 19.5))
