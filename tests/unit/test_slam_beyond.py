"""Property tests of the reference library ``slamcourse.slam`` (SE(2), odometry EKF, pose graphs).

Group axioms and wrapping for :mod:`se2`; Jacobians against central finite differences for
:mod:`ekf` and :mod:`posegraph`; gauge freedom and gauge invariance of pose graphs.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import ekf, se2

FAST = settings(max_examples=150, deadline=None)
coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
poses = st.tuples(coord, coord, heading)
angles = st.floats(-1e3, 1e3, allow_nan=False, allow_infinity=False)


def close_pose(a: tuple[float, ...], b: tuple[float, ...], tol: float = 1e-9) -> bool:
    return (
        abs(a[0] - b[0]) <= tol
        and abs(a[1] - b[1]) <= tol
        and abs(se2.wrap_angle(a[2] - b[2])) <= tol
    )


# --- se2 --------------------------------------------------------------------------------------


@FAST
@given(angles)
def test_wrap_lands_in_half_open_interval_and_is_idempotent(a: float) -> None:
    w = se2.wrap_angle(a)
    assert -math.pi < w <= math.pi
    assert se2.wrap_angle(w) == w
    assert math.cos(w) == pytest.approx(math.cos(a), abs=1e-9)
    assert math.sin(w) == pytest.approx(math.sin(a), abs=1e-9)


def test_wrap_boundaries() -> None:
    assert se2.wrap_angle(math.pi) == math.pi
    assert se2.wrap_angle(-math.pi) == math.pi
    assert se2.wrap_angle(0.0) == 0.0
    assert se2.wrap_angle(5.5) == pytest.approx(5.5 - 2 * math.pi)


def test_compose_by_hand() -> None:
    assert se2.compose((1, 0, math.pi / 2), (1, 0, 0)) == pytest.approx((1, 1, math.pi / 2))
    assert se2.between((1, 1, math.pi / 2), (1, 3, math.pi)) == pytest.approx((2, 0, math.pi / 2))
    assert se2.inverse((2, 1, math.pi / 2)) == pytest.approx((-1, 2, -math.pi / 2))


@FAST
@given(poses, poses)
def test_between_undoes_compose(x: se2.Pose, y: se2.Pose) -> None:
    assert close_pose(se2.compose(x, se2.between(x, y)), y)


@FAST
@given(poses, poses, poses)
def test_compose_is_associative_and_matches_matrices(a: se2.Pose, b: se2.Pose, c: se2.Pose) -> None:
    left = se2.compose(se2.compose(a, b), c)
    right = se2.compose(a, se2.compose(b, c))
    assert close_pose(left, right, 1e-8)
    product = se2.to_matrix(a) @ se2.to_matrix(b)
    assert close_pose(se2.from_matrix(product), se2.compose(a, b))


@FAST
@given(poses)
def test_inverse_is_a_two_sided_inverse(a: se2.Pose) -> None:
    identity = (0.0, 0.0, 0.0)
    assert close_pose(se2.compose(a, se2.inverse(a)), identity)
    assert close_pose(se2.compose(se2.inverse(a), a), identity)
    assert close_pose(se2.from_matrix(np.linalg.inv(se2.to_matrix(a))), se2.inverse(a))


@FAST
@given(poses, poses, poses)
def test_between_is_invariant_under_a_global_motion(g: se2.Pose, a: se2.Pose, b: se2.Pose) -> None:
    moved = se2.between(se2.compose(g, a), se2.compose(g, b))
    assert close_pose(moved, se2.between(a, b), 1e-8)


# --- ekf --------------------------------------------------------------------------------------

turns = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
motions = st.tuples(turns, st.floats(0.0, 5.0, allow_nan=False, allow_infinity=False), turns)


@FAST
@given(poses, motions)
def test_motion_jacobians_match_central_differences(pose: se2.Pose, u: se2.Pose) -> None:
    g = ekf.jacobian_state(pose, u)
    v = ekf.jacobian_control(pose, u)
    g_num = ekf.numerical_jacobian(lambda p: ekf.odometry_step(p, u), pose)
    v_num = ekf.numerical_jacobian(lambda q: ekf.odometry_step(pose, q), u)
    assert np.allclose(g, g_num, atol=1e-7)
    assert np.allclose(v, v_num, atol=1e-7)


@FAST
@given(poses, motions)
def test_odometry_step_is_a_composition(pose: se2.Pose, u: se2.Pose) -> None:
    rot1, trans, rot2 = u
    composed = se2.compose(se2.compose(pose, (0.0, 0.0, rot1)), (trans, 0.0, rot2))
    assert close_pose(ekf.odometry_step(pose, u), composed, 1e-9)


def test_prediction_keeps_the_covariance_symmetric_positive_definite() -> None:
    rng = np.random.default_rng(7)
    for _ in range(50):
        a = rng.normal(size=(3, 3))
        b = rng.normal(size=(3, 3)) * 0.1
        sigma, m = a @ a.T + 1e-3 * np.eye(3), b @ b.T + 1e-4 * np.eye(3)
        pose = tuple(rng.uniform(-5, 5, size=3))
        u = (rng.uniform(-1, 1), rng.uniform(0, 3), rng.uniform(-1, 1))
        _, cov = ekf.predict(pose, sigma, u, m)
        assert np.allclose(cov, cov.T)
        assert np.linalg.eigvalsh(cov).min() > 0
        g = ekf.jacobian_state(pose, u)
        # the motion's noise only adds uncertainty to what G carries over
        assert np.linalg.eigvalsh(cov - g @ sigma @ g.T).min() > -1e-12
