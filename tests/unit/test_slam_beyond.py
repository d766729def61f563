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

from slamcourse.slam import ekf, posegraph, se2

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


# --- posegraph --------------------------------------------------------------------------------

measurements = st.tuples(
    st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False),
    st.floats(-5.0, 5.0, allow_nan=False, allow_infinity=False),
    heading,
)


@FAST
@given(poses, poses, measurements)
def test_edge_jacobians_match_central_differences(xi: se2.Pose, xj: se2.Pose, z: se2.Pose) -> None:
    a, b = posegraph.edge_jacobians(xi, xj, z)
    a_num = ekf.numerical_jacobian(lambda p: posegraph.edge_error(p, xj, z), xi)
    b_num = ekf.numerical_jacobian(lambda p: posegraph.edge_error(xi, p, z), xj)
    assert np.allclose(a, a_num, atol=1e-6)
    assert np.allclose(b, b_num, atol=1e-6)


@FAST
@given(poses, poses, measurements)
def test_edge_error_vanishes_on_agreement_and_matches_matrices(
    xi: se2.Pose, xj: se2.Pose, z: se2.Pose
) -> None:
    assert np.allclose(posegraph.edge_error(xi, se2.compose(xi, z), z), 0, atol=1e-9)
    product = np.linalg.inv(se2.to_matrix(z)) @ np.linalg.inv(se2.to_matrix(xi)) @ se2.to_matrix(xj)
    assert close_pose(tuple(posegraph.edge_error(xi, xj, z)), se2.from_matrix(product), 1e-8)


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 10), st.integers(0, 3), poses)
def test_chi2_is_invariant_under_a_global_motion_and_h_has_a_3d_null_space(
    seed: int, n: int, loops: int, g: se2.Pose
) -> None:
    x, edges = posegraph.simulate(seed, n, loops)
    moved = np.array([se2.compose(g, p) for p in x])
    assert posegraph.chi2(moved, edges) == pytest.approx(posegraph.chi2(x, edges), rel=1e-9)
    h, _ = posegraph.linear_system(x, edges)
    eigenvalues = np.linalg.eigvalsh(h)
    assert np.sum(np.abs(eigenvalues) < 1e-8 * eigenvalues.max()) == 3
    assert np.linalg.matrix_rank(h[3:, 3:]) == 3 * n - 3  # anchoring pose 0 removes it


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 10), st.integers(0, 3), poses)
def test_gauss_newton_converges_to_a_stationary_point_whatever_the_gauge(
    seed: int, n: int, loops: int, g: se2.Pose
) -> None:
    x, edges = posegraph.simulate(seed, n, loops)
    optimised, history = posegraph.gauss_newton(x, edges, 10)
    assert history[-1] <= history[0] + 1e-9
    _, grad = posegraph.linear_system(optimised, edges)
    assert np.abs(grad).max() < 1e-6 * max(1.0, history[0])
    # the same graph placed elsewhere in the world, and anchored at its last pose instead
    moved = np.array([se2.compose(g, p) for p in x])
    other, _ = posegraph.gauss_newton(moved, edges, 10, anchor=n - 1)
    assert np.allclose(
        posegraph.relative_to_first(other), posegraph.relative_to_first(optimised), atol=1e-7
    )


def test_dense_and_sparse_systems_agree() -> None:
    x, edges = posegraph.simulate(3, 8, 3)
    h, b = posegraph.linear_system(x, edges)
    slow_h, slow_b = np.zeros_like(h), np.zeros_like(b)
    for edge in edges:
        e = posegraph.edge_error(x[edge.i], x[edge.j], edge.z)
        a, bj = posegraph.edge_jacobians(x[edge.i], x[edge.j], edge.z)
        jac = np.zeros((3, len(b)))
        jac[:, 3 * edge.i : 3 * edge.i + 3] = a
        jac[:, 3 * edge.j : 3 * edge.j + 3] = bj
        slow_h += jac.T @ edge.information @ jac
        slow_b += jac.T @ edge.information @ e
    assert np.allclose(h, slow_h) and np.allclose(b, slow_b)
    step = posegraph.gauss_newton_step(x, edges)
    dense = np.linalg.solve(h[3:, 3:], -b[3:])
    assert np.allclose(step[1:, :2], x[1:, :2] + dense.reshape(-1, 3)[:, :2])


def test_toy_graphs_reach_their_known_chi2() -> None:
    for text, start, end in ((NOISY_TOY, 0.783275, 0.136652),):
        graph = posegraph.parse_g2o(text)
        _, history = posegraph.gauss_newton(graph.poses, graph.edges, 5)
        assert history[0] == pytest.approx(start, abs=1e-6)
        assert history[-1] == pytest.approx(end, abs=1e-6)


# GTSAM examples/Data/noisyToyGraph.txt (BSD licence, Georgia Tech Research Corporation)
NOISY_TOY = """\
VERTEX_SE2 0 0.000000 0.000000 0.000000
VERTEX_SE2 1 0.774115 1.183389 1.576173
VERTEX_SE2 2 -0.262420 2.047059 -3.127594
VERTEX_SE2 3 -1.605649 0.993891 -1.561134
EDGE_SE2 0 1 0.774115 1.183389 1.576173 1.000000 0.000000 0.000000 1.000000 0.000000 1.000000
EDGE_SE2 1 2 0.869231 1.031877 1.579418 1.000000 0.000000 0.000000 1.000000 0.000000 1.000000
EDGE_SE2 2 3 1.357840 1.034262 1.566460 1.000000 0.000000 0.000000 1.000000 0.000000 1.000000
EDGE_SE2 2 0 0.303492 1.865011 -3.113898 1.000000 0.000000 0.000000 1.000000 0.000000 1.000000
EDGE_SE2 0 3 -0.928526 0.993695 -1.563542 1.000000 0.000000 0.000000 1.000000 0.000000 1.000000
"""


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.integers(2, 6), st.integers(1, 12))
def test_one_step_solves_a_linear_problem_exactly(seed: int, n: int, extra: int) -> None:
    """With pose 0 fixed and every edge leaving pose 0, each error is linear in the free pose
    (``B`` is constant) as long as no angular error crosses ±π, so one Gauss-Newton step lands
    on the minimum: the gradient vanishes and a second step does not move."""
    rng = np.random.default_rng(seed)
    x = np.column_stack([rng.uniform(-5, 5, (n, 2)), rng.uniform(-1, 1, n)])
    x[:, 2] += rng.uniform(-3, 3)  # angular errors stay within (−π, π]: wrapping never kicks in
    targets = [1 + k % (n - 1) for k in range(n - 1 + extra)]  # every free pose, some twice
    edges = []
    for k in targets:
        z = (float(rng.uniform(-3, 3)), float(rng.uniform(-3, 3)), float(rng.uniform(-1, 1)))
        root = np.eye(3) + rng.uniform(-0.3, 0.3, (3, 3))
        edges.append(posegraph.Edge(0, k, z, root.T @ root))
    once = posegraph.gauss_newton_step(x, edges)
    _, grad = posegraph.linear_system(once, edges)
    assert np.abs(grad[3:]).max() < 1e-8
    twice = posegraph.gauss_newton_step(once, edges)
    assert np.allclose(twice, once, atol=1e-10)
