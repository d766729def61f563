"""Property tests of :mod:`slamcourse.slam.victoria` (landmark SLAM on GTSAM's text format).

The x-y factor and GTSAM's bearing-range reading against central differences; the stacked
factors against the single-factor functions; ``H`` against a dense ``Jᵀ Ω J``; Gauss-Newton's
answer independent of the gauge; the EKF's steps against the filter chapters' formulas
(:mod:`slamcourse.slam.ekfslam`); the redundancies against a dense inverse.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import ekf, ekfslam, se2
from slamcourse.slam import victoria as vp

FAST = settings(max_examples=100, deadline=None)
coord = st.floats(-300.0, 300.0, allow_nan=False, allow_infinity=False)
near = st.floats(-30.0, 30.0, allow_nan=False, allow_infinity=False)
heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)

TEXT = """\
ODOMETRY 0 1 1.0 0.0 0.1 0.0004 0.0001 0 0.0009 0 0.0016
LANDMARK 1 2 5.0 1.0 0.09 0.02 0.25

ODOMETRY 1 3 1.0 0.05 0.2 0.0004 0 0 0.0009 0 0.0016\r
LANDMARK 3 2 3.9 0.3 0.1 0 0.3
LANDMARK 3 5 2.0 -4.0 0.2 0.05 0.1
ODOMETRY 3 4 1.1 -0.02 -0.1 0.0005 0 0.0001 0.001 0 0.002
LANDMARK 4 2 2.9 -0.2 0.1 0 0.1
LANDMARK 4 5 1.2 -3.5 0.2 0 0.2"""


def test_parse_shared_ids_and_covariances() -> None:
    data = vp.parse_victoria(TEXT)
    assert data.pose_ids == (0, 1, 3, 4) and data.landmark_ids == (2, 5)
    assert data.odometry_from.tolist() == [0, 1, 2] and data.odometry_to.tolist() == [1, 2, 3]
    assert data.seen_from.tolist() == [1, 2, 2, 3, 3] and data.seen.tolist() == [0, 0, 1, 0, 1]
    assert data.odometry_cov[0].tolist() == [[4e-4, 1e-4, 0], [1e-4, 9e-4, 0], [0, 0, 1.6e-3]]
    assert data.measured_cov[2].tolist() == [[0.2, 0.05], [0.05, 0.1]]
    # the edges carry the information, the inverse of the file's covariance
    assert np.allclose(data.edges[2].information @ data.odometry_cov[2], np.eye(3))
    assert vp.degrees_of_freedom(data) == 2 * (5 - 2)


@FAST
@given(coord, coord, heading, near, near)
def test_landmark_jacobians_match_central_differences(
    x: float, y: float, t: float, dx: float, dy: float
) -> None:
    pose, tree, z = (x, y, t), (x + dx, y + dy), (3.0, -1.0)
    a, b = vp.landmark_jacobians(pose, tree)
    num = ekf.numerical_jacobian(
        lambda v: vp.landmark_error(v[:3], v[3:], z), [*pose, *tree], step=1e-6, angle_rows=()
    )
    assert np.allclose(np.hstack([a, b]), num, atol=1e-6)


@FAST
@given(coord, coord, heading, near, near)
def test_inverse_landmark_inverts_the_prediction(
    x: float, y: float, t: float, dx: float, dy: float
) -> None:
    pose = (x, y, t)
    z = vp.predict_landmark(pose, (x + dx, y + dy))
    assert np.allclose(vp.inverse_landmark(pose, z), (x + dx, y + dy), atol=1e-9)
    # the same as the pose graph's frame change applied to a point
    rel = se2.between(pose, (x + dx, y + dy, 0.0))
    assert np.allclose(z, rel[:2], atol=1e-9)


def test_gtsam_sigmas() -> None:
    assert vp.gtsam_sigmas(0.4) == pytest.approx((0.2, math.sqrt(0.4)))


def _state(seed: int, data: vp.LandmarkData) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    x, trees = vp.initial_guess(data)
    return x + rng.normal(0, 0.2, x.shape), trees + rng.normal(0, 0.5, trees.shape)


def test_stacked_terms_match_single_factors() -> None:
    data = vp.parse_victoria(vp.simulate(3, 12, 5, True))
    x, trees = _state(0, data)
    e, jac, om = vp.xy_terms(x, trees, data)
    for k in range(len(e)):
        i, lm, z = data.seen_from[k], data.seen[k], data.measured[k]
        a, b = vp.landmark_jacobians(x[i], trees[lm])
        assert np.allclose(e[k], vp.landmark_error(x[i], trees[lm], z))
        assert np.allclose(jac[k], np.hstack([a, b]))
        assert np.allclose(om[k] @ data.measured_cov[k], np.eye(2))


def test_range_bearing_terms_match_central_differences() -> None:
    data = vp.parse_victoria(vp.simulate(5, 10, 4))
    x, trees = _state(1, data)
    e, jac, om = vp.range_bearing_terms(x, trees, data)
    for k in range(len(e)):
        i, lm = data.seen_from[k], data.seen[k]
        z = data.measured[k]

        def f(v: np.ndarray, z: np.ndarray = z) -> np.ndarray:
            d = v[3:] - v[:2]
            b = se2.wrap_angle(math.atan2(d[1], d[0]) - v[2] - math.atan2(z[1], z[0]))
            return np.array([b, math.hypot(d[0], d[1]) - math.hypot(z[0], z[1])])

        point = [*x[i], *trees[lm]]
        assert np.allclose(e[k], f(np.array(point)))
        num = ekf.numerical_jacobian(f, point, step=1e-6, angle_rows=(0,))
        assert np.allclose(jac[k], num, atol=1e-6)
        sb, sr = vp.gtsam_sigmas(data.measured_cov[k, 0, 0])
        assert np.allclose(om[k], np.diag([1 / sb**2, 1 / sr**2]))


def test_normal_equations_equal_a_dense_sum() -> None:
    data = vp.parse_victoria(vp.simulate(7, 9, 4, True))
    x, trees = _state(2, data)
    h, g = vp.normal_equations(x, trees, data)
    size = 3 * data.n + 2 * data.m
    dense_h, dense_g = np.zeros((size, size)), np.zeros(size)
    for edge in data.edges:
        e = np.array(se2.compose(se2.inverse(edge.z), se2.between(x[edge.i], x[edge.j])))
        from slamcourse.slam import posegraph as pg

        a, b = pg.edge_jacobians(x[edge.i], x[edge.j], edge.z)
        j = np.zeros((3, size))
        j[:, 3 * edge.i : 3 * edge.i + 3], j[:, 3 * edge.j : 3 * edge.j + 3] = a, b
        dense_h += j.T @ edge.information @ j
        dense_g += j.T @ edge.information @ e
    for k in range(len(data.measured)):
        i, lm = data.seen_from[k], data.seen[k]
        a, b = vp.landmark_jacobians(x[i], trees[lm])
        j = np.zeros((2, size))
        j[:, 3 * i : 3 * i + 3], j[:, 3 * data.n + 2 * lm : 3 * data.n + 2 * lm + 2] = a, b
        om = np.linalg.inv(data.measured_cov[k])
        dense_h += j.T @ om @ j
        dense_g += j.T @ om @ vp.landmark_error(x[i], trees[lm], data.measured[k])
    assert np.allclose(h.toarray(), dense_h)  # type: ignore[attr-defined]
    assert np.allclose(g, dense_g)


@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_the_optimum_does_not_depend_on_the_gauge(seed: int) -> None:
    """Moving the whole initial guess rigidly changes no relative state at convergence."""
    data = vp.parse_victoria(vp.simulate(seed, 15, 6, seed % 2 == 1))
    x, trees = vp.initial_guess(data)
    a, la, _ = vp.converge(x, trees, data)
    move = (4.0, -7.0, 2.5)
    moved = np.array([se2.compose(move, p) for p in x])
    lifted = np.array([vp.inverse_landmark(move, t) for t in trees])
    b, lb, _ = vp.converge(moved, lifted, data)
    assert np.allclose(vp.relative_state(a, la), vp.relative_state(b, lb), atol=1e-8)
    # and the optimum is stationary: the gradient b = Σ Jᵀ Ω e vanishes there
    _, g = vp.normal_equations(a, la, data)
    assert np.max(np.abs(g[3:])) < 1e-6


def test_optimise_with_zero_steps_is_the_initial_guess() -> None:
    data = vp.parse_victoria(TEXT)
    x, trees = vp.initial_guess(data)
    assert np.allclose(vp.optimise(TEXT, 0), np.concatenate([x.ravel(), trees.ravel()]))
    # pose 3 (id 4) is the odometry composed; tree 2 sits where pose 1 first saw it
    p = se2.compose(se2.compose((1.0, 0.0, 0.1), (1.0, 0.05, 0.2)), (1.1, -0.02, -0.1))
    assert np.allclose(x[3], p)
    assert np.allclose(trees[0], vp.inverse_landmark((1.0, 0.0, 0.1), (5.0, 1.0)))


def test_ekf_steps_match_the_filter_chapters() -> None:
    rng = np.random.default_rng(4)
    root = rng.normal(size=(7, 7))
    p = root @ root.T
    mean = rng.normal(size=7)
    z, m = np.array([1.0, 0.1, 0.2]), np.diag([1e-3, 2e-3, 3e-3])
    # prediction: F P Fᵀ + F_x V M Vᵀ F_xᵀ with the full F
    got_mean, got_p = mean.copy(), p.copy()
    vp.ekf_predict(got_mean, got_p, z, m)
    theta = mean[2]
    c, s = math.cos(theta), math.sin(theta)
    f = np.eye(7)
    f[:3, :3] = [[1, 0, -s * z[0] - c * z[1]], [0, 1, c * z[0] - s * z[1]], [0, 0, 1]]
    v = np.zeros((7, 3))
    v[:3] = [[c, -s, 0], [s, c, 0], [0, 0, 1]]
    assert np.allclose(got_p, f @ p @ f.T + v @ m @ v.T)
    assert np.allclose(got_mean[:3], se2.compose(mean[:3], z))
    # update: the Joseph form of ekfslam and the x-y innovation
    r = np.array([[0.2, 0.05], [0.05, 0.3]])
    new_mean, new_p, nis = vp.ekf_update(mean, p, 3, np.array([2.0, -1.0]), r)
    a, b = vp.landmark_jacobians(mean[:3], mean[3:5])
    h = np.zeros((2, 7))
    h[:, :3], h[:, 3:5] = a, b
    assert np.allclose(new_p, ekfslam.update_covariance(p, h, r))
    nu = np.array([2.0, -1.0]) - vp.predict_landmark(mean[:3], mean[3:5])
    k = ekfslam.kalman_gain(p, h, r)
    expect = mean + k @ nu
    expect[2] = se2.wrap_angle(expect[2])
    assert np.allclose(new_mean, expect)
    assert nis == pytest.approx(nu @ np.linalg.solve(h @ p @ h.T + r, nu))


def test_ekf_on_noise_free_lines_recovers_the_truth() -> None:
    """Lines written from the true poses and trees: the filter ends on them exactly."""
    truth = [(0.0, 0.0, 0.0)]
    for k in range(20):
        truth.append(se2.compose(truth[-1], (1.0, 0.0, 0.2 if k % 4 else -0.1)))
    trees = [(3.0, 2.0), (6.0, -1.0), (2.0, 6.0)]
    lines = []
    for k, t in enumerate(truth):
        if k:
            z = se2.between(truth[k - 1], t)
            lines.append(f"ODOMETRY {k - 1} {k} {z[0]!r} {z[1]!r} {z[2]!r} 1e-4 0 0 1e-4 0 1e-4")
        for j, tree in enumerate(trees):
            z2 = vp.predict_landmark(t, tree)
            lines.append(f"LANDMARK {k} {100 + j} {float(z2[0])!r} {float(z2[1])!r} 0.1 0 0.1")
    data = vp.parse_victoria("\n".join(lines))
    run = vp.ekf_slam(data)
    assert run.order == (0, 1, 2)
    assert np.allclose(run.mean[3:].reshape(-1, 2), trees, atol=1e-9)
    assert np.allclose(run.poses, truth, atol=1e-9)
    assert np.allclose(run.nis, 0.0, atol=1e-12)


def test_redundancy_matches_a_dense_inverse() -> None:
    data = vp.parse_victoria(vp.simulate(11, 25, 6, True))
    x, trees = vp.initial_guess(data)
    x, trees, _ = vp.converge(x, trees, data)
    r_odo, r_obs = vp.redundancy(x, trees, data)
    h, _ = vp.normal_equations(x, trees, data)
    cov = np.linalg.inv(h.toarray()[3:, 3:])  # type: ignore[attr-defined]
    full = np.zeros((h.shape[0], h.shape[0]))  # type: ignore[attr-defined]
    full[3:, 3:] = cov
    lev = {"odo": 0.0, "obs": 0.0}
    for edge in data.edges:
        from slamcourse.slam import posegraph as pg

        a, b = pg.edge_jacobians(x[edge.i], x[edge.j], edge.z)
        j = np.zeros((3, h.shape[0]))  # type: ignore[attr-defined]
        j[:, 3 * edge.i : 3 * edge.i + 3], j[:, 3 * edge.j : 3 * edge.j + 3] = a, b
        lev["odo"] += float(np.trace(edge.information @ j @ full @ j.T))
    for k in range(len(data.measured)):
        i, lm = data.seen_from[k], data.seen[k]
        a, b = vp.landmark_jacobians(x[i], trees[lm])
        j = np.zeros((2, h.shape[0]))  # type: ignore[attr-defined]
        j[:, 3 * i : 3 * i + 3], j[:, 3 * data.n + 2 * lm : 3 * data.n + 2 * lm + 2] = a, b
        lev["obs"] += float(np.trace(np.linalg.inv(data.measured_cov[k]) @ j @ full @ j.T))
    assert r_odo == pytest.approx(3 * len(data.edges) - lev["odo"], abs=1e-6)
    assert r_obs == pytest.approx(2 * len(data.measured) - lev["obs"], abs=1e-6)
    assert r_odo + r_obs == pytest.approx(vp.degrees_of_freedom(data), abs=1e-6)


def test_incremental_reaches_the_batch_optimum_on_a_small_drive() -> None:
    data = vp.parse_victoria(vp.simulate(2, 30, 8))
    x, trees = vp.initial_guess(data)
    a, la, _ = vp.converge(x, trees, data)
    b, lb, stages = vp.incremental(data, stride=10)
    assert [s.poses for s in stages] == [10, 20, 30]
    assert np.allclose(vp.relative_state(a, la), vp.relative_state(b, lb), atol=1e-8)
    assert stages[-1].chi2_after == pytest.approx(vp.chi2(a, la, data), rel=1e-9)
    assert stages[-1].dof == vp.degrees_of_freedom(data)


def test_window_and_subproblem() -> None:
    text = vp.simulate(9, 20, 5)
    piece = vp.parse_victoria(vp.window(text, 5, 8))
    full = vp.parse_victoria(text)
    assert piece.pose_ids == full.pose_ids[5:13]
    assert len(piece.odometry) == 7
    seen = [k for k in range(len(full.measured)) if 5 <= full.seen_from[k] < 13]
    assert len(piece.measured) == len(seen)
    sub = vp.subproblem(full, 8)
    assert sub.pose_ids == full.pose_ids[:8] and len(sub.edges) == 7
    assert set(sub.landmark_ids) == {full.landmark_ids[k] for k in full.seen[full.seen_from < 8]}


def test_simulate_shares_ids_or_shuffles_them() -> None:
    plain = vp.parse_victoria(vp.simulate(1, 12, 5))
    ids = sorted(plain.pose_ids + plain.landmark_ids)
    assert ids == list(range(len(ids)))
    shuffled = vp.simulate(4, 12, 5, shuffle_ids=True)
    data = vp.parse_victoria(shuffled)
    first = list(dict.fromkeys(data.seen.tolist()))
    assert first != sorted(first)  # the trees' ids do not follow their first sightings
    assert np.all(np.linalg.eigvalsh(data.measured_cov) > 0)
    assert np.all(np.linalg.eigvalsh(data.odometry_cov) > 0)
