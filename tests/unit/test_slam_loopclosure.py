"""Property tests of :mod:`slamcourse.slam.loopclosure` against independent computations.

Jacobians against central differences; the relative covariance against a full-graph
Jacobian applied to the whole ``H⁻¹``; the covariance's gauge invariance; the odometry
recursion against ``H⁻¹`` of the chain; the NIS against the equivalent route in pose ``i``'s
frame; the χ² gates against printed tables; the candidate search against a brute force.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import loopclosure as lc
from slamcourse.slam import posegraph as pg
from slamcourse.slam import se2

FAST = settings(max_examples=100, deadline=None)
coord = st.floats(-30.0, 30.0, allow_nan=False, allow_infinity=False)
heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
poses = st.tuples(coord, coord, heading)


def numeric_jacobian(xi: se2.Pose, xj: se2.Pose, h: float = 1e-6) -> np.ndarray:
    x = np.array([*xi, *xj], dtype=float)
    out = np.zeros((3, 6))
    for k in range(6):
        up, down = x.copy(), x.copy()
        up[k] += h
        down[k] -= h
        a, b = np.array(se2.between(up[:3], up[3:])), np.array(se2.between(down[:3], down[3:]))
        diff = a - b
        diff[2] = se2.wrap_angle(diff[2])
        out[:, k] = diff / (2 * h)
    return out


@FAST
@given(poses, poses)
def test_relative_jacobians_match_central_differences(xi: se2.Pose, xj: se2.Pose) -> None:
    ji, jj = lc.relative_jacobians(xi, xj)
    assert np.allclose(np.hstack([ji, jj]), numeric_jacobian(xi, xj), atol=1e-6)


@pytest.fixture(scope="module")
def graph() -> tuple[np.ndarray, list[pg.Edge]]:
    x, edges = pg.simulate(7, 12, 3)
    opt, _ = pg.gauss_newton(x, edges, 15)
    return opt, list(edges)


def test_relative_covariance_equals_full_graph_propagation(
    graph: tuple[np.ndarray, list[pg.Edge]],
) -> None:
    """Σ_r from the two poses' blocks equals J_full H⁻¹ J_fullᵀ with a 3×3n Jacobian built by
    finite differences over the whole state."""
    x, edges = graph
    cov = lc.covariance(x, edges)
    for i, j in ((2, 9), (0, 11), (5, 6), (10, 3)):
        jac = np.zeros((3, 3 * len(x)))
        local = numeric_jacobian(x[i], x[j])
        jac[:, 3 * i : 3 * i + 3] += local[:, :3]
        jac[:, 3 * j : 3 * j + 3] += local[:, 3:]
        expected = jac @ cov @ jac.T
        got = lc.relative_pose_covariance(
            x[i], x[j], lc.block(cov, i, i), lc.block(cov, i, j), lc.block(cov, j, j)
        )
        assert np.allclose(got, expected, rtol=1e-6, atol=1e-12)


def test_relative_covariance_does_not_depend_on_the_anchor(
    graph: tuple[np.ndarray, list[pg.Edge]],
) -> None:
    x, edges = graph
    c0, c7 = lc.covariance(x, edges, anchor=0), lc.covariance(x, edges, anchor=7)
    for i, j in ((2, 9), (4, 5), (1, 10)):
        r0 = lc.relative_pose_covariance(
            x[i], x[j], lc.block(c0, i, i), lc.block(c0, i, j), lc.block(c0, j, j)
        )
        r7 = lc.relative_pose_covariance(
            x[i], x[j], lc.block(c7, i, i), lc.block(c7, i, j), lc.block(c7, j, j)
        )
        assert np.allclose(r0, r7, rtol=1e-6, atol=1e-12)
    assert np.all(c7[21:24] == 0) and np.all(c0[:3] == 0)


def test_covariance_inverts_the_anchored_information(
    graph: tuple[np.ndarray, list[pg.Edge]],
) -> None:
    x, edges = graph
    h, _ = pg.linear_system(x, edges)
    cov = lc.covariance(x, edges)
    assert np.allclose(h[3:, 3:] @ cov[3:, 3:], np.eye(len(h) - 3), atol=1e-8)


def test_odometry_recursion_equals_the_chain_inverse() -> None:
    _, edges = pg.simulate(11, 30, 0)
    chain = list(edges)
    dead = [(0.0, 0.0, 0.3)]
    for e in chain:
        dead.append(se2.compose(dead[-1], e.z))
    dr = np.array(dead)
    cov = lc.covariance(dr, chain)
    rec = lc.odometry_covariances(dr, chain)
    for k in range(len(dr)):
        assert np.allclose(rec[k], lc.block(cov, k, k), rtol=1e-9, atol=1e-14)
    # the heading variance only adds up along the chain (positions may not: lever arms shrink
    # when the path turns back)
    var = [float(rec[k][2, 2]) for k in range(len(dr))]
    assert all(b > a for a, b in itertools.pairwise(var))


def _random_joint(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    m = rng.normal(size=(6, 6)) * np.array([0.5, 0.5, 0.1, 0.5, 0.5, 0.1])
    return np.asarray(m @ m.T + 1e-3 * np.eye(6))


@FAST
@given(poses, poses, st.integers(0, 10_000))
def test_nis_equals_the_route_in_pose_i_frame(xi: se2.Pose, dz: se2.Pose, seed: int) -> None:
    """``e`` with ``S`` (measurement frame) and ``r − z`` with ``Σ_r + R_z Ω⁻¹ R_zᵀ`` (pose i's
    frame) are the same statistic."""
    rng = np.random.default_rng(seed)
    xj = se2.compose(xi, (dz[0] / 10, dz[1] / 10, dz[2]))
    z = (dz[0] / 10 + rng.normal(0, 0.3), dz[1] / 10 + rng.normal(0, 0.3), rng.uniform(-3, 3))
    p = _random_joint(seed)
    root = np.eye(3) + rng.uniform(-0.3, 0.3, (3, 3))
    info = root.T @ np.diag([100.0, 30.0, 400.0]) @ root
    got = lc.closure_nis(xi, xj, p[:3, :3], p[:3, 3:], p[3:, 3:], z, info)
    r = np.array(se2.between(xi, xj))
    nu = np.array([r[0] - z[0], r[1] - z[1], se2.wrap_angle(r[2] - z[2])])
    rz = np.eye(3)
    rz[:2, :2] = se2.rotation(z[2])
    s = lc.relative_pose_covariance(xi, xj, p[:3, :3], p[:3, 3:], p[3:, 3:])
    s = s + rz @ np.linalg.inv(info) @ rz.T
    assert got == pytest.approx(float(nu @ np.linalg.solve(s, nu)), rel=1e-7, abs=1e-12)


def test_gates_match_printed_tables() -> None:
    # chi-square tables (e.g. NIST/SEMATECH e-Handbook, table 1.3.6.7.4)
    assert lc.chi2_gate(3, 0.95) == pytest.approx(7.815, abs=1e-3)
    assert lc.chi2_gate(3, 0.99) == pytest.approx(11.345, abs=1e-3)
    assert lc.chi2_gate(2, 0.95) == pytest.approx(5.991, abs=1e-3)
    assert lc.chi2_gate(2, 0.99) == pytest.approx(9.210, abs=1e-3)


def test_candidates_match_a_brute_force(graph: tuple[np.ndarray, list[pg.Edge]]) -> None:
    x, edges = graph
    cov = lc.covariance(x, edges)
    n, k = len(x), len(x) - 1
    marginals = np.array([lc.block(cov, i, i) for i in range(n)])
    cross = np.array([lc.block(cov, i, k) for i in range(n)])
    d2 = lc.candidate_distances(x, marginals, cross, 3)
    assert sorted(d2) == list(range(0, k - 3 + 1))

    def _blocks(i: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return marginals[i], cross[i], marginals[k]

    for i, value in d2.items():
        jac = np.zeros((2, 3 * n))
        local = numeric_jacobian(x[i], x[k])[:2]
        jac[:, 3 * i : 3 * i + 3] += local[:, :3]
        jac[:, 3 * k : 3 * k + 3] += local[:, 3:]
        t = np.array(se2.between(x[i], x[k])[:2])
        assert value == pytest.approx(float(t @ np.linalg.solve(jac @ cov @ jac.T, t)), rel=1e-5)
    idx, r, s = lc.relative_positions(x, marginals, cross, 3)
    for i, ri, si in zip(idx, r, s, strict=True):  # pose by pose, the 3×3 route
        assert np.allclose(ri, se2.between(x[i], x[k])[:2], atol=1e-12)
        full = lc.relative_pose_covariance(x[i], x[k], marginals[i], cross[i], marginals[k])
        assert np.allclose(si, full[:2, :2], rtol=1e-10, atol=1e-14)
        assert d2[int(i)] == pytest.approx(lc.position_d2(x[i], x[k], *_blocks(i)), rel=1e-9)
    for gate in (1.0, 5.99, 50.0):
        got = lc.loop_candidates(x, marginals, cross, 3, gate)
        assert got == [i for i in sorted(d2) if d2[i] <= gate]


def test_two_dof_gate_has_a_closed_form() -> None:
    """χ²₂ is the exponential distribution of mean 2: its quantile is −2 ln(1 − p) (the
    chapter's closed form, which the candidate search may use instead of scipy)."""
    for p in (0.5, 0.9, 0.95, 0.99, 0.999):
        assert lc.chi2_gate(2, p) == pytest.approx(-2 * math.log(1 - p), rel=1e-12)


def test_candidate_search_window(graph: tuple[np.ndarray, list[pg.Edge]]) -> None:
    """Pose ``k − gap`` is searched and ``k − gap + 1`` is not; a gap as long as the history
    leaves nothing; indices come back increasing."""
    x, edges = graph
    cov = lc.covariance(x, edges)
    n, k = len(x), len(x) - 1
    marginals = np.array([lc.block(cov, i, i) for i in range(n)])
    cross = np.array([lc.block(cov, i, k) for i in range(n)])
    for gap in (1, 4, k):
        assert max(lc.candidate_distances(x, marginals, cross, gap)) == k - gap
        everything = lc.loop_candidates(x, marginals, cross, gap, 1e12)
        assert everything == list(range(k - gap + 1))
    assert lc.loop_candidates(x, marginals, cross, k + 1, 1e12) == []
    assert lc.candidate_distances(x, marginals, cross, n + 5) == {}


def test_ellipse_axes() -> None:
    a, b, ang = lc.ellipse([[4.0, 0.0], [0.0, 1.0]], 2.0)
    assert (a, b) == pytest.approx((4.0, 2.0))
    assert math.cos(ang) ** 2 == pytest.approx(1.0)


def test_joint_covariance_by_sparse_solves_equals_the_dense_inverse(
    graph: tuple[np.ndarray, list[pg.Edge]],
) -> None:
    x, edges = graph
    cov = lc.covariance(x, edges, anchor=2)
    for i, j in ((2, 9), (0, 11), (7, 3)):
        idx = [*range(3 * i, 3 * i + 3), *range(3 * j, 3 * j + 3)]
        expected = cov[np.ix_(idx, idx)]
        assert np.allclose(lc.joint_covariance(x, edges, i, j, anchor=2), expected, atol=1e-12)


def test_sideways_variance_grows_like_the_cube_of_the_distance() -> None:
    """The prose: on a straight drive with equal noise per edge, the heading variance grows
    linearly and the sideways variance it causes like the cube of the distance."""
    info = np.diag([1 / 0.05**2, 1 / 0.05**2, 1 / 0.01**2])
    chain = [pg.Edge(k, k + 1, (1.0, 0.0, 0.0), info) for k in range(400)]
    dead = np.array([[float(k), 0.0, 0.0] for k in range(401)])
    rec = lc.odometry_covariances(dead, chain)
    assert rec[400][2, 2] / rec[200][2, 2] == pytest.approx(2.0)
    assert rec[400][1, 1] / rec[200][1, 1] == pytest.approx(8.0, rel=0.01)
