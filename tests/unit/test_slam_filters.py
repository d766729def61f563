"""Property tests of the filter half of the reference library: :mod:`slamcourse.slam.ekfslam`.

The update keeps ``P`` a covariance (symmetric, positive semi-definite), never raises its trace,
does nothing with an infinitely noisy sensor, and its Joseph and short forms agree; the inverse
observation model inverts the observation model, and its Jacobians (and the observation's)
match central finite differences.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import consistency, ekfslam, jcbb
from slamcourse.slam.ekf import numerical_jacobian
from slamcourse.slam.se2 import wrap_angle

FAST = settings(max_examples=60, deadline=None)
coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)


@st.composite
def filter_states(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, int]:
    """A state with 1–3 landmarks 1–20 m from the robot, a covariance ``L Lᵀ`` (variances
    0.001–1) and the index of one landmark."""
    landmarks = draw(st.integers(1, 3))
    mu = [draw(coord), draw(coord), draw(heading)]
    for _ in range(landmarks):
        d, a = draw(st.floats(1.0, 20.0)), draw(heading)
        mu += [mu[0] + d * math.cos(a), mu[1] + d * math.sin(a)]
    n = len(mu)
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))  # the matrix from a seed: fast
    low = np.tril(rng.uniform(-0.6, 0.6, (n, n)), -1) + np.diag(rng.uniform(0.3, 1.0, n))
    scale = draw(st.sampled_from([0.01, 0.1, 1.0]))
    return np.array(mu), low @ low.T * scale, draw(st.integers(0, landmarks - 1))


@st.composite
def noises(draw: st.DrawFn) -> np.ndarray:
    """A correlated range-bearing noise covariance (σ_r 5–50 cm, σ_φ 0.005–0.05 rad)."""
    sr, sb, rho = (
        draw(st.floats(0.05, 0.5)),
        draw(st.floats(0.005, 0.05)),
        draw(st.floats(-0.8, 0.8)),
    )
    return np.array([[sr * sr, rho * sr * sb], [rho * sr * sb, sb * sb]])


def _is_psd(m: np.ndarray) -> bool:
    return bool(np.linalg.eigvalsh((m + m.T) / 2).min() >= -1e-12 * max(1.0, np.abs(m).max()))


@FAST
@given(filter_states(), noises())
def test_update_keeps_a_symmetric_psd_covariance_with_no_larger_trace(
    state: tuple[np.ndarray, np.ndarray, int], r: np.ndarray
) -> None:
    mu, p, j = state
    h = ekfslam.observation_jacobian(mu, j)
    p_new = ekfslam.update_covariance(p, h, r)
    assert np.allclose(p_new, p_new.T, atol=1e-12)
    assert _is_psd(p_new)
    assert np.trace(p_new) <= np.trace(p) + 1e-12
    # no single variance grows either: P − P⁺ = K S Kᵀ is positive semi-definite
    assert _is_psd(p - p_new)


@FAST
@given(filter_states(), noises())
def test_joseph_and_short_forms_agree(
    state: tuple[np.ndarray, np.ndarray, int], r: np.ndarray
) -> None:
    mu, p, j = state
    h = ekfslam.observation_jacobian(mu, j)
    joseph = ekfslam.update_covariance(p, h, r)
    short = ekfslam.update_covariance_simple(p, h, r)
    assert np.allclose(joseph, short, rtol=1e-8, atol=1e-12)
    # and both equal the information form (P⁻¹ + Hᵀ R⁻¹ H)⁻¹
    info = np.linalg.inv(np.linalg.inv(p) + h.T @ np.linalg.solve(r, h))
    assert np.allclose(joseph, info, rtol=1e-6, atol=1e-10)


@FAST
@given(filter_states(), noises(), st.floats(0.05, 0.5), st.floats(-0.05, 0.05))
def test_an_infinitely_noisy_sensor_changes_nothing(
    state: tuple[np.ndarray, np.ndarray, int], r: np.ndarray, dr: float, db: float
) -> None:
    mu, p, j = state
    h_pred = ekfslam.observe(mu[:3], mu[3 + 2 * j : 5 + 2 * j])
    z = h_pred + np.array([dr, db])
    hj = ekfslam.observation_jacobian(mu, j)
    mu_new, p_new = ekfslam.update(mu, p, z, h_pred, hj, r * 1e16)
    step = mu_new - mu
    step[2] = wrap_angle(step[2])  # a heading at π may come back as −π: the same angle
    assert np.allclose(step, 0, atol=1e-9)
    assert np.allclose(p_new, p, atol=1e-9)
    # a useful sensor does move the state towards the measurement
    mu_used, _ = ekfslam.update(mu, p, z, h_pred, hj, r)
    assert not np.allclose(mu_used, mu, atol=1e-9)


def test_gain_of_one_number_and_the_sparsity_of_k() -> None:
    assert ekfslam.kalman_gain([[0.04]], [[1.0]], [[0.01]])[0, 0] == pytest.approx(0.8)
    # landmark 3 uncorrelated with everything: its gain rows are zero
    p = np.eye(9)
    p[0, 3] = p[3, 0] = p[3, 5] = p[5, 3] = 0.3
    h = ekfslam.observation_jacobian([0, 0, 0, 4, 3, -2, 6, 10, -1], 0)
    k = ekfslam.kalman_gain(p, h, np.eye(2) * 0.01)
    assert np.abs(k[7:]).max() == 0
    assert np.abs(k[5:7]).max() > 0  # landmark 2: never observed, but correlated
    kh = k @ h
    assert set(np.flatnonzero(np.abs(kh).sum(axis=0))) <= {0, 1, 2, 3, 4}


def test_update_wraps_the_bearing_innovation_and_the_heading() -> None:
    mu = np.array([0.0, 0.0, 3.1, -5.0, 0.05])
    p = np.diag([0.01, 0.01, 0.04, 0.01, 0.01])
    h_pred = ekfslam.observe(mu[:3], mu[3:])  # bearing close to +π
    z = [h_pred[0], wrap_angle(h_pred[1] + 0.2)]  # measured 0.2 rad further left: across ±π
    nu = ekfslam.innovation(z, h_pred)
    assert nu[1] == pytest.approx(0.2)
    mu_new, _ = ekfslam.update(
        mu, p, z, h_pred, ekfslam.observation_jacobian(mu, 0), np.diag([0.01, 0.001])
    )
    assert -math.pi < mu_new[2] <= math.pi
    assert abs(wrap_angle(mu_new[2] - mu[2])) < 0.2  # the heading moved a little, not by 2π


@FAST
@given(coord, coord, heading, st.floats(0.5, 30.0), heading)
def test_inverse_observation_inverts_the_observation(
    x: float, y: float, t: float, r: float, phi: float
) -> None:
    landmark = ekfslam.inverse_observation((x, y, t), (r, phi))
    back = ekfslam.observe((x, y, t), landmark)
    assert back[0] == pytest.approx(r, rel=1e-9)
    assert abs(wrap_angle(back[1] - phi)) < 1e-9


@FAST
@given(coord, coord, heading, st.floats(0.5, 30.0), heading)
def test_inverse_jacobians_match_finite_differences(
    x: float, y: float, t: float, r: float, phi: float
) -> None:
    g_r = numerical_jacobian(
        lambda v: ekfslam.inverse_observation(v, (r, phi)), (x, y, t), angle_rows=()
    )
    g_z = numerical_jacobian(
        lambda v: ekfslam.inverse_observation((x, y, t), v), (r, phi), angle_rows=()
    )
    assert np.allclose(ekfslam.inverse_jacobian_pose((x, y, t), (r, phi)), g_r, atol=1e-6)
    assert np.allclose(ekfslam.inverse_jacobian_measurement((x, y, t), (r, phi)), g_z, atol=1e-6)


@FAST
@given(filter_states())
def test_observation_jacobian_matches_finite_differences(
    state: tuple[np.ndarray, np.ndarray, int],
) -> None:
    mu, _, j = state

    def h(v: np.ndarray) -> np.ndarray:
        return ekfslam.observe(v[:3], v[3 + 2 * j : 5 + 2 * j])

    numeric = numerical_jacobian(h, mu, angle_rows=(1,))
    assert np.allclose(ekfslam.observation_jacobian(mu, j), numeric, atol=1e-6)


@FAST
@given(filter_states(), noises(), st.floats(0.5, 30.0), heading)
def test_augment_is_the_linearised_map_of_state_and_measurement(
    state: tuple[np.ndarray, np.ndarray, int], r: np.ndarray, rng: float, phi: float
) -> None:
    mu, p, _ = state
    mu_new, p_new = ekfslam.augment(mu, p, (rng, phi), r)
    n = mu.size
    assert mu_new.shape == (n + 2,) and p_new.shape == (n + 2, n + 2)
    assert np.array_equal(p_new[:n, :n], p)  # the old block is copied unchanged
    assert np.allclose(p_new, p_new.T) and _is_psd(p_new)

    # the same covariance from a numerical Jacobian of (x, z) ↦ (x, g(x_r, z)) and blockdiag(P, R)
    def lifted(v: np.ndarray) -> np.ndarray:
        return np.concatenate([v[:n], ekfslam.inverse_observation(v[:3], v[n:])])

    jac = numerical_jacobian(lifted, np.concatenate([mu, [rng, phi]]), angle_rows=())
    joint = np.zeros((n + 2, n + 2))
    joint[:n, :n], joint[n:, n:] = p, r
    assert np.allclose(p_new, jac @ joint @ jac.T, rtol=1e-6, atol=1e-7)


# --- jcbb -------------------------------------------------------------------------------------


def _scene() -> tuple[np.ndarray, np.ndarray, list[np.ndarray], np.ndarray]:
    """Two landmarks 1.2 m apart, 10 m ahead; the true heading is 0.1 rad more than believed."""
    mu = np.array([0.0, 0.0, 0.0, 10.0, 0.0, 10.0, 1.2])
    p = np.diag([0.01, 0.01, 0.02, 0.01, 0.01, 0.01, 0.01])
    truth = (0.0, 0.0, 0.1)
    zs = [ekfslam.observe(truth, mu[3:5]), ekfslam.observe(truth, mu[5:7])]
    return mu, p, zs, np.diag([0.04, 0.0004])


def test_greedy_pairs_both_with_one_landmark_and_jcbb_does_not() -> None:
    mu, p, zs, r = _scene()
    assert jcbb.greedy_nn(mu, p, zs, r, 0.95) == (0, 0)
    assert jcbb.jcbb(mu, p, zs, r, 0.95) == (0, 1)
    assert jcbb.exhaustive(mu, p, zs, r, 0.95) == (0, 1)
    # the right pairing is less surprising jointly than its two individual tests added up
    joint = jcbb.hypothesis_d2(mu, p, zs, r, (0, 1))
    apart = jcbb.hypothesis_d2(mu, p, zs, r, (0, -1)) + jcbb.hypothesis_d2(mu, p, zs, r, (-1, 1))
    assert joint < 0.6 * apart
    assert jcbb.hypothesis_d2(mu, p, zs, r, (1, 0)) > jcbb.joint_gate(2, 0.95)


@st.composite
def scans(draw: st.DrawFn) -> tuple[np.ndarray, np.ndarray, list[np.ndarray], np.ndarray]:
    """A state with 2–3 landmarks, and 1–3 noisy measurements of some of them (or of clutter)
    taken from a pose drawn from the filter's own uncertainty."""
    mu, p, _ = draw(filter_states())
    landmarks = (mu.size - 3) // 2
    if landmarks < 2:
        mu = np.concatenate([mu, mu[:2] + np.array([3.0, 4.0])])
        p = np.pad(p, ((0, 2), (0, 2))) + np.diag([0.0] * (mu.size - 2) + [0.05, 0.05])
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    truth = rng.multivariate_normal(mu, p)
    r = draw(noises())
    zs = []
    for _ in range(draw(st.integers(1, 3))):
        j = draw(st.integers(-1, (mu.size - 3) // 2 - 1))
        spot = truth[3 + 2 * j : 5 + 2 * j] if j >= 0 else truth[:2] + rng.uniform(-10, 10, 2)
        zs.append(ekfslam.observe(truth[:3], spot) + rng.multivariate_normal([0, 0], r))
    return mu, p, zs, r


@settings(max_examples=40, deadline=None)
@given(scans())
def test_jcbb_is_jointly_compatible_and_pairs_at_least_as_many_as_nn(
    scan: tuple[np.ndarray, np.ndarray, list[np.ndarray], np.ndarray],
) -> None:
    mu, p, zs, r = scan
    picked = jcbb.jcbb(mu, p, zs, r, 0.95)
    used = [j for j in picked if j >= 0]
    assert len(used) == len(set(used))
    assert jcbb.jointly_compatible(mu, p, zs, r, picked, 0.95)
    # no subset of nearest neighbour's pairs that JCBB could reach (distinct landmarks, every
    # prefix in measurement order jointly compatible: the branches it follows) pairs more
    nn = jcbb.greedy_nn(mu, p, zs, r, 0.95)
    for mask in range(1 << len(zs)):
        subset = tuple(j if mask >> i & 1 else -1 for i, j in enumerate(nn))
        kept = [j for j in subset if j >= 0]
        reachable = all(
            jcbb.jointly_compatible(mu, p, zs, r, subset[:i] + (-1,) * (len(zs) - i), 0.95)
            for i in range(1, len(zs) + 1)
        )
        if len(kept) == len(set(kept)) and reachable:
            assert len(kept) <= len(used)
    # and it never pairs fewer than brute force finds, except where a prefix fails its gate
    best = jcbb.exhaustive(mu, p, zs, r, 0.95)
    assert len(used) <= sum(1 for j in best if j >= 0)


@FAST
@given(filter_states(), noises(), st.integers(0, 2**32 - 1))
def test_joint_d2_of_a_sub_hypothesis_is_never_larger(
    state: tuple[np.ndarray, np.ndarray, int], r: np.ndarray, seed: int
) -> None:
    mu, p, _ = state
    landmarks = (mu.size - 3) // 2
    h = np.vstack([ekfslam.observation_jacobian(mu, j) for j in range(landmarks)])
    nu = np.random.default_rng(seed).normal(size=2 * landmarks) * 0.1
    full = jcbb.joint_d2(h, p, r, nu)
    for i in range(landmarks):  # drop pairing i: the marginal distance cannot grow
        keep = [k for k in range(2 * landmarks) if k // 2 != i]
        if keep:
            assert jcbb.joint_d2(h[keep], p, r, nu[keep]) <= full * (1 + 1e-9) + 1e-12
    # one pairing: the joint test is the individual one
    s = h[:2] @ p @ h[:2].T + r
    assert jcbb.joint_d2(h[:2], p, r, nu[:2]) == pytest.approx(nu[:2] @ np.linalg.solve(s, nu[:2]))


# --- consistency ------------------------------------------------------------------------------


@pytest.mark.parametrize(("dof", "runs"), [(1, 1), (2, 1), (2, 50), (3, 50), (6, 25), (3, 100)])
def test_average_band_matches_scipy(dof: int, runs: int) -> None:
    from scipy.stats import chi2

    low, high = consistency.average_band(dof, runs, 0.95)
    assert low == pytest.approx(chi2.ppf(0.025, dof * runs) / runs, rel=1e-8)
    assert high == pytest.approx(chi2.ppf(0.975, dof * runs) / runs, rel=1e-8)


def test_band_narrows_around_n_as_runs_grow() -> None:
    widths = [np.subtract(*consistency.average_band(3, runs)[::-1]) for runs in (1, 10, 100)]
    assert widths[0] > widths[1] > widths[2]
    low, high = consistency.average_band(3, 100)
    assert low < 3 < high


def test_nees_of_gaussian_errors_averages_n() -> None:
    rng = np.random.default_rng(7)
    low = np.array([[0.3, 0, 0], [0.1, 0.2, 0], [0.05, -0.02, 0.1]])
    p = low @ low.T
    errors = rng.multivariate_normal(np.zeros(3), p, size=4000)
    values = [consistency.nees(e, np.zeros(3), p) for e in errors]
    assert np.mean(values) == pytest.approx(3, rel=0.05)


@FAST
@given(filter_states(), heading)
def test_nees_wraps_the_heading_and_nothing_else(
    state: tuple[np.ndarray, np.ndarray, int], shift: float
) -> None:
    mu, p, _ = state
    x_hat = mu.copy()
    x_hat[2] = wrap_angle(mu[2] + shift)
    # a heading error is the same error whichever way it is written modulo 2π
    expected = consistency.nees([0, 0, -shift], [0, 0, 0], p[:3, :3], angle_indices=(2,))
    assert consistency.nees(mu[:3], x_hat[:3], p[:3, :3], angle_indices=(2,)) == pytest.approx(
        expected, rel=1e-6, abs=1e-9
    )
    # the sign of the error does not matter
    assert consistency.nees(mu, x_hat, p, (2,)) == pytest.approx(
        consistency.nees(x_hat, mu, p, (2,)), rel=1e-9
    )


def test_simulated_filters_are_diagnosed() -> None:
    consistent = consistency.simulate_anees(1.0, runs=50, steps=20, seed=1)
    overconfident = consistency.simulate_anees(0.1, runs=50, steps=20, seed=1)
    verdicts = [consistency.diagnose(a, 2, 50) for a in consistent]
    assert verdicts.count("consistent") >= 17  # about 95 % of the steps
    assert [consistency.diagnose(a, 2, 50) for a in overconfident[5:]].count("over-confident") >= 13
    assert consistency.nis([0.3, -0.09], [[0.25, 0], [0, 0.01]]) == pytest.approx(1.17)
