"""slamcourse.slam.se3 against independent computations (scipy's Rotation, finite differences,
matrix exponentials), and the conventions of sphere2500 checked against its ground truth."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import expm, logm  # type: ignore[import-untyped]
from scipy.spatial.transform import Rotation  # type: ignore[import-untyped]

from slamcourse.slam import se3

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "exercises" / "se3" / "data"
RNG = np.random.default_rng(2208)


def _axes(count: int) -> np.ndarray:
    v = RNG.normal(size=(count, 3))
    out: np.ndarray = v / np.linalg.norm(v, axis=1, keepdims=True)
    return out


def test_exp_matches_the_matrix_exponential_and_scipy() -> None:
    for n, theta in zip(
        _axes(30), np.concatenate([[0, 1e-9, 1e-5, 1e-3], RNG.uniform(0, 3.2, 26)]), strict=True
    ):
        w = theta * n
        assert np.allclose(se3.so3_exp(w), expm(se3.hat(w)), atol=1e-13)
        assert np.allclose(se3.so3_exp(w), Rotation.from_rotvec(w).as_matrix(), atol=1e-13)
    xi = RNG.normal(size=6)
    twist = np.zeros((4, 4))
    twist[:3, :3], twist[:3, 3] = se3.hat(xi[3:]), xi[:3]
    assert np.allclose(se3.se3_exp(xi), expm(twist), atol=1e-12)
    assert np.allclose(se3.se3_log(se3.se3_exp(xi)), xi, atol=1e-12)
    assert np.allclose(
        se3.so3_exp(np.stack([xi[3:], -xi[3:]])), [expm(se3.hat(xi[3:])), expm(-se3.hat(xi[3:]))]
    )


def test_trace_formula_of_the_angle() -> None:
    for n in _axes(5):
        theta = float(RNG.uniform(0, math.pi))
        r = Rotation.from_rotvec(theta * n).as_matrix()
        assert np.trace(r) == pytest.approx(1 + 2 * math.cos(theta), abs=1e-12)


def test_log_against_scipy_in_every_regime() -> None:
    for k, n in enumerate(_axes(400)):
        regime = k % 3
        theta = (
            RNG.uniform(0, math.pi)
            if regime == 0
            else 10 ** RNG.uniform(-9, -2)
            if regime == 1
            else math.pi - 10 ** RNG.uniform(-12, -1)
        )
        r = se3.so3_exp(theta * n)
        expected = Rotation.from_matrix(r).as_rotvec()
        assert np.allclose(se3.so3_log(r), expected, rtol=1e-7, atol=1e-12)


def test_log_at_exactly_pi_makes_the_largest_component_positive() -> None:
    for n in _axes(50):
        r = 2 * np.outer(n, n) - np.eye(3)
        w = se3.so3_log(r)
        k = int(np.argmax(np.abs(n)))
        assert w[k] > 0
        assert np.allclose(np.abs(w), math.pi * np.abs(n), atol=1e-12)
        # and it is a logarithm: the skew matrix's exponential gives R back (scipy's logm is
        # ambiguous at π, so compare the exponential instead)
        assert np.allclose(expm(se3.hat(w)), r, atol=1e-12)
    assert np.allclose(se3.so3_log(np.diag([1.0, -1.0, -1.0])), [math.pi, 0, 0])


def test_log_matches_logm_in_the_middle() -> None:
    for n in _axes(5):
        r = se3.so3_exp(2.0 * n)
        assert np.allclose(se3.hat(se3.so3_log(r)), np.real(logm(r)), atol=1e-10)


def test_quaternions_double_cover() -> None:
    q = np.array([0.5, 0.5, 0.5, 0.5])
    assert np.allclose(se3.quaternion_to_matrix(q), se3.quaternion_to_matrix(-q))
    # scipy writes (x, y, z, w)
    assert np.allclose(
        se3.quaternion_to_matrix(q), Rotation.from_quat([0.5, 0.5, 0.5, 0.5]).as_matrix()
    )
    assert Rotation.from_quat([0.5, 0.5, 0.5, 0.5]).magnitude() == pytest.approx(2 * math.pi / 3)
    for n in _axes(10):
        r = se3.so3_exp(float(RNG.uniform(0, math.pi)) * n)
        assert np.allclose(se3.quaternion_to_matrix(se3.matrix_to_quaternion(r)), r, atol=1e-12)
    p, s = (
        se3.matrix_to_quaternion(se3.so3_exp([0.1, 0.2, 0.3])),
        se3.matrix_to_quaternion(se3.so3_exp([-0.3, 0.5, 0.1])),
    )
    assert np.allclose(
        se3.quaternion_to_matrix(se3.quaternion_multiply(p, s)),
        se3.so3_exp([0.1, 0.2, 0.3]) @ se3.so3_exp([-0.3, 0.5, 0.1]),
    )


def test_rpy_is_rz_ry_rx() -> None:
    angles = [0.3, -0.4, 2.5]
    assert np.allclose(
        se3.rpy_matrix(*angles), Rotation.from_euler("xyz", angles).as_matrix(), atol=1e-14
    )
    assert np.allclose(se3.rpy_angles(se3.rpy_matrix(*angles)), angles)


def test_right_jacobians_by_finite_differences() -> None:
    h = 1e-6
    for w in [np.array([0.3, -0.2, 0.5]), np.array([1e-6, 0, 2e-6]), np.array([1.0, 2.0, -1.5])]:
        numeric = np.zeros((3, 3))
        for k in range(3):
            d = np.zeros(3)
            d[k] = h
            numeric[:, k] = (
                se3.so3_log(se3.so3_exp(w) @ se3.so3_exp(d))
                - se3.so3_log(se3.so3_exp(w) @ se3.so3_exp(-d))
            ) / (2 * h)
        assert np.allclose(se3.right_jacobian_inverse(w), numeric, atol=1e-7)
        assert np.allclose(se3.right_jacobian(w) @ se3.right_jacobian_inverse(w), np.eye(3))


def test_adjoint_moves_a_left_step_to_the_right() -> None:
    x = se3.se3_exp(RNG.normal(size=6))
    d = RNG.normal(size=6) * 0.3
    assert np.allclose(
        se3.se3_exp(d) @ x, x @ se3.se3_exp(se3.adjoint(se3.inverse(x)) @ d), atol=1e-12
    )


def _graph_and_poses() -> tuple[se3.Graph3, np.ndarray]:
    _, text = se3.simulate(3, 6, 4, correlated=True)
    graph = se3.parse_edge3(text)
    x = graph.poses @ se3.se3_exp(RNG.normal(size=(6, 6)) * 0.05)
    return graph, x


def test_edge_jacobians_by_central_differences() -> None:
    graph, x = _graph_and_poses()
    _, a, b = se3.edge_errors(x, graph)
    h = 1e-6
    for k in range(len(graph.i)):
        i, j = int(graph.i[k]), int(graph.j[k])
        for which, jac in ((i, a[k]), (j, b[k])):
            numeric = np.zeros((6, 6))
            for c in range(6):
                d = np.zeros(6)
                d[c] = h
                plus, minus = x.copy(), x.copy()
                plus[which] = x[which] @ se3.se3_exp(d)
                minus[which] = x[which] @ se3.se3_exp(-d)
                numeric[:, c] = (
                    se3.edge_errors(plus, graph)[0][k] - se3.edge_errors(minus, graph)[0][k]
                ) / (2 * h)
            assert np.allclose(jac, numeric, atol=1e-6)
    jy = se3.between_jacobians(x[0], x[1])
    assert np.allclose(jy[0], -se3.adjoint(se3.between(x[1], x[0])))


def test_sparse_step_equals_a_dense_solve() -> None:
    graph, x = _graph_and_poses()
    e, a, b = se3.edge_errors(x, graph)
    n = len(x)
    h = np.zeros((6 * n, 6 * n))
    g = np.zeros(6 * n)
    for k in range(len(e)):
        jac = np.zeros((6, 6 * n))
        jac[:, 6 * graph.i[k] : 6 * graph.i[k] + 6] += a[k]
        jac[:, 6 * graph.j[k] : 6 * graph.j[k] + 6] += b[k]
        h += jac.T @ graph.omega[k] @ jac
        g += jac.T @ graph.omega[k] @ e[k]
    delta = np.zeros(6 * n)
    delta[6:] = np.linalg.solve(h[6:, 6:], -g[6:])
    assert np.allclose(se3.gauss_newton_step(x, graph), x @ se3.se3_exp(delta.reshape(n, 6)))
    # the same step with the unknowns in the minimum-degree order (a large graph's), and with
    # another pose held fixed: the order's indices skip the anchor's six
    for anchor in (0, 2, n - 1):
        order = se3.elimination_order(n, graph, anchor)
        assert sorted(order.tolist()) == list(range(6 * (n - 1)))
        fixed = np.r_[0 : 6 * anchor, 6 * anchor + 6 : 6 * n]
        delta = np.zeros(6 * n)
        delta[fixed] = np.linalg.solve(h[np.ix_(fixed, fixed)], -g[fixed])
        step = se3.gauss_newton_step(x, graph, anchor=anchor, order=order)
        assert np.allclose(step, x @ se3.se3_exp(delta.reshape(n, 6)))


def test_align_recovers_a_rigid_motion() -> None:
    p = RNG.normal(size=(50, 3))
    r = Rotation.from_rotvec([0.3, -1.0, 2.0]).as_matrix()
    q = p @ r.T + [1.0, -2.0, 3.0]
    assert np.allclose(se3.align(p, q), q)
    assert se3.ate_rmse(p, q) == pytest.approx(0, abs=1e-12)


# --- sphere2500: the conventions, checked against the ground truth ----------------------------


def _rows(name: str) -> tuple[np.ndarray, np.ndarray]:
    rows = [line.split() for line in (DATA / name).read_text(encoding="utf-8").splitlines()]
    ij = np.array([[int(f[1]), int(f[2])] for f in rows])
    return ij, np.array([[float(v) for v in f[3:]] for f in rows])


def _closure_residuals(make_rotation: object) -> float:
    """Largest rotation disagreement (rad) of a noise-free loop closure with the composed
    noise-free odometry, the angles turned into matrices by ``make_rotation`` (scipy)."""
    ij, values = _rows("sphere2500_groundtruth.txt")
    rot = make_rotation(values[:, 3:6])  # type: ignore[operator]
    n = int(ij.max()) + 1
    odometry = {(int(a), int(b)): k for k, (a, b) in enumerate(ij) if b == a + 1}
    orientation = [np.eye(3)]
    for k in range(1, n):
        orientation.append(orientation[-1] @ rot[odometry[(k - 1, k)]])
    worst = 0.0
    for k, (a, b) in enumerate(ij):
        if b != a + 1:
            err = rot[k].T @ orientation[a].T @ orientation[b]
            worst = max(worst, float(Rotation.from_matrix(err).magnitude()))
    return worst


def test_sphere2500_files_and_counts() -> None:
    ij, values = _rows("sphere2500.txt")
    assert (len(ij), int(ij.max()) + 1) == (4949, 2500)
    assert int(np.sum(ij[:, 1] - ij[:, 0] != 1)) == 2450
    assert values.shape[1] == 27
    shared = ROOT.parent / "shared" / "data" / "gtsam_3d_and_landmarks"
    for name in ("sphere2500.txt", "sphere2500_groundtruth.txt"):
        if (shared / name).exists():
            assert (DATA / name).read_bytes() == (shared / name).read_bytes()


def test_sphere2500_rotation_convention() -> None:
    """Rz(yaw) Ry(pitch) Rx(roll) closes every loop to printing precision; Rx Ry Rz does not."""
    right = _closure_residuals(lambda a: Rotation.from_euler("xyz", a).as_matrix())
    wrong = _closure_residuals(lambda a: Rotation.from_euler("XYZ", a).as_matrix())
    assert right < 5e-6  # prose: "at most 4e-6 rad"
    assert 0.011 < wrong < 0.013  # prose: "up to 0.012 rad"
    assert np.allclose(
        se3.rpy_matrix(0.1, -0.2, 0.3), Rotation.from_euler("xyz", [0.1, -0.2, 0.3]).as_matrix()
    )


def test_sphere2500_numbers_are_square_root_information() -> None:
    """The noise (noisy against true edges) is 1/S: 0.1 m, 0.01 rad (roll, pitch), 0.04 rad."""
    _, noisy = _rows("sphere2500.txt")
    _, true = _rows("sphere2500_groundtruth.txt")
    to_pose = lambda v: se3.pose(Rotation.from_euler("xyz", v[:, 3:6]).as_matrix(), v[:, :3])  # noqa: E731
    diff = se3.inverse(to_pose(true)) @ to_pose(noisy)
    residual = np.concatenate(
        [diff[:, :3, 3], Rotation.from_matrix(diff[:, :3, :3]).as_rotvec()], axis=1
    )
    sigma = residual.std(axis=0)
    assert sigma == pytest.approx(
        [0.1, 0.1, 0.1, 0.01, 0.01, 0.04], rel=0.05
    )  # prose: 0.100, 0.010, 0.040
    s_diagonal = noisy[0, 6:][[0, 6, 11, 15, 18, 20]]
    assert list(s_diagonal) == [10, 10, 10, 100, 100, 25]
    assert 1 / s_diagonal == pytest.approx(sigma, rel=0.05)
