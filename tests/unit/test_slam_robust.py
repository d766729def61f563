"""Property tests of :mod:`slamcourse.slam.robust`: kernels, IRLS, Levenberg-Marquardt, outliers.

Kernels against scipy's own least-squares losses (which apply ρ to the squared residual, the
course's convention) and against central differences; IRLS's fixed point against the gradient
of the robust cost by finite differences; Levenberg-Marquardt's limits against a dense solve.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from slamcourse.slam import posegraph as pg
from slamcourse.slam import robust as rb

FAST = settings(max_examples=100, deadline=None)
widths = st.floats(0.5, 10.0, allow_nan=False)
squares = st.lists(st.floats(0.0, 1e4, allow_nan=False), min_size=1, max_size=20)


def _scipy_loss(name: str, s: np.ndarray, k: float) -> tuple[np.ndarray, np.ndarray]:
    """scipy's loss ``ρ(z)`` on ``z = s/k²``, scaled by ``k²`` as least_squares does with
    ``f_scale = k``: (cost, derivative by s)."""
    import importlib

    lsq = importlib.import_module("scipy.optimize._lsq.least_squares")  # its loss functions
    rho = np.empty((3, len(s)))
    getattr(lsq, name)(s / k**2, rho, cost_only=False)
    return k**2 * rho[0], rho[1]


@FAST
@given(squares, widths)
def test_huber_and_cauchy_match_scipy(s: list[float], k: float) -> None:
    arr = np.array(s)
    for kind in ("huber", "cauchy"):
        cost, weight = _scipy_loss(kind, arr, k)
        assert np.allclose(rb.kernel_cost(kind, arr, k), cost, rtol=1e-12, atol=1e-9)
        assert np.allclose(rb.kernel_weights(kind, arr, k), weight, rtol=1e-12, atol=1e-15)


@FAST
@given(st.floats(1e-3, 1e4, allow_nan=False), widths, st.sampled_from(rb.KERNELS))
def test_weight_is_the_derivative_of_the_cost(s: float, k: float, kind: str) -> None:
    if abs(s - k * k) < 1e-3 * k * k:  # the kink of Huber and DCS
        return
    h = 1e-6 * max(s, 1.0)
    numeric = (rb.kernel_cost(kind, [s + h], k) - rb.kernel_cost(kind, [s - h], k))[0] / (2 * h)
    assert rb.kernel_weights(kind, [s], k)[0] == pytest.approx(numeric, rel=1e-5, abs=1e-9)


@FAST
@given(widths)
def test_kernels_at_zero_at_the_boundary_and_far_out(k: float) -> None:
    for kind in rb.KERNELS:
        assert rb.kernel_weights(kind, [0.0], k)[0] == 1.0
        assert rb.kernel_cost(kind, [0.0], k)[0] == 0.0
    for kind in ("huber", "dcs"):  # continuous, weight 1 at s = k²
        below, above = rb.kernel_cost(kind, [k * k * (1 - 1e-12), k * k * (1 + 1e-12)], k)
        assert below == pytest.approx(above, rel=1e-9)
        assert rb.kernel_weights(kind, [k * k], k)[0] == pytest.approx(1.0)
    # DCS: Agarwal et al.'s scale of the error, squared; its cost is bounded by 3Φ
    s = 1e8
    assert rb.kernel_weights("dcs", [s], k)[0] == pytest.approx((2 * k * k / (k * k + s)) ** 2)
    assert rb.kernel_cost("dcs", [s], k)[0] < 3 * k * k


def test_unknown_kernel_and_bad_width() -> None:
    with pytest.raises(ValueError):
        rb.kernel_weights("tukey", [1.0], 1.0)
    with pytest.raises(ValueError):
        rb.kernel_weights("huber", [1.0], 0.0)


def _graph_with_outliers(seed: int) -> tuple[np.ndarray, list[pg.Edge]]:
    poses, edges = pg.simulate(seed, 12, 3)
    return poses, [*edges, *rb.false_loop_closures(poses, edges, 2, seed, 3)]


@pytest.mark.parametrize(("kind", "k"), [("huber", 2.0), ("cauchy", 2.0), ("dcs", 3.0)])
def test_irls_settles_at_a_stationary_point_of_the_robust_cost(kind: str, k: float) -> None:
    """The gradient of Σρ (loop closures) + Σs (odometry), by central differences over every
    coordinate of poses 1…n−1, vanishes where IRLS stops."""
    poses, edges = _graph_with_outliers(4)
    x, history = rb.irls(poses, edges, kind, k, 60)
    assert history[-1] == pytest.approx(history[-2], rel=1e-10)
    start_grad = []
    for point in (poses, x):
        grad = []
        for idx in range(3, 3 * len(point)):
            d = np.zeros(3 * len(point))
            d[idx] = 1e-6
            up = rb.robust_cost(point + d.reshape(-1, 3), edges, kind, k)
            down = rb.robust_cost(point - d.reshape(-1, 3), edges, kind, k)
            grad.append((up - down) / 2e-6)
        start_grad.append(np.linalg.norm(grad))
    assert start_grad[1] < 1e-5 * start_grad[0]


def test_irls_with_least_squares_is_gauss_newton() -> None:
    poses, edges = _graph_with_outliers(7)
    a, _ = rb.irls(poses, edges, "l2", 1.0, 5)
    b, _ = pg.gauss_newton(poses, edges, 5)
    assert np.allclose(a, b, atol=1e-12)


def _dense(poses: np.ndarray, edges: list[pg.Edge]) -> tuple[np.ndarray, np.ndarray]:
    h, b = pg.linear_system(poses, edges)
    return h[3:, 3:], b[3:]


def test_damped_step_limits_and_predicted_reduction() -> None:
    poses, edges = pg.simulate(3, 8, 2)
    h, b = _dense(poses, edges)
    chi = pg.chi2(poses, edges)
    # λ → 0: the Gauss-Newton step
    y, _ = rb.damped_step(poses, edges, 1e-12, marquardt=False)
    assert np.allclose(y, pg.gauss_newton_step(poses, edges), atol=1e-8)
    # λ → ∞ (Levenberg): the step tends to −b/λ
    lam = 1e12
    y, predicted = rb.damped_step(poses, edges, lam, marquardt=False)
    step = (y - poses)[1:].ravel()
    assert np.allclose(lam * step, -b, rtol=1e-4, atol=1e-6 * np.abs(b).max())
    # the predicted reduction is χ² − L(Δ), L the linearised χ² (dense, by its definition)
    for lam, marquardt in ((0.1, True), (3.0, False)):
        y, predicted = rb.damped_step(poses, edges, lam, marquardt)
        d = (y - poses)[1:].ravel()
        d_pose = np.concatenate([np.zeros(3), d])
        e, a_jac, b_jac, om = pg.stacked_errors(poses, edges)
        model = 0.0
        for k, edge in enumerate(edges):
            lin = e[k] + a_jac[k] @ d_pose[3 * edge.i : 3 * edge.i + 3]
            lin = lin + b_jac[k] @ d_pose[3 * edge.j : 3 * edge.j + 3]
            model += float(lin @ om[k] @ lin)
        assert predicted == pytest.approx(chi - model, rel=1e-8)
        assert predicted > 0
        damping = np.diag(np.diag(h)) if marquardt else np.eye(len(b))
        assert np.allclose((h + lam * damping) @ d, -b, rtol=1e-8, atol=1e-8 * np.abs(b).max())


def test_levenberg_marquardt_never_rises_and_reaches_the_optimum() -> None:
    poses, edges = pg.simulate(11, 10, 3)
    gn, _ = pg.gauss_newton(poses, edges, 15)
    x, history, lambdas = rb.levenberg_marquardt(poses, edges, 40, 1.0)
    assert all(b <= a for a, b in itertools.pairwise(history))
    assert history[-1] == pytest.approx(pg.chi2(gn, edges), rel=1e-9)
    assert np.allclose(pg.relative_to_first(x), pg.relative_to_first(gn), atol=1e-6)
    assert len(lambdas) == 40


def test_gain_ratio() -> None:
    assert rb.gain_ratio(1200, 900, 480) == pytest.approx(0.625)


@FAST
@given(st.integers(0, 2**32 - 1), st.integers(0, 30))
def test_false_loop_closures(seed: int, count: int) -> None:
    poses, edges = pg.simulate(seed % 1000, 60, 3)
    bad = rb.false_loop_closures(poses, edges, count, seed)
    assert len(bad) == count
    sources = [e.information for e in edges if abs(e.i - e.j) > 1]
    for e in bad:
        assert 0 <= e.i < e.j < 60 and e.j - e.i >= 50
        assert all(abs(v) <= 2 for v in e.z[:2]) and -math.pi <= e.z[2] < math.pi
        assert any(np.array_equal(e.information, s) for s in sources)
    again = rb.false_loop_closures(poses, edges, count + 3, seed)
    assert [(e.i, e.j, e.z) for e in again[:count]] == [(e.i, e.j, e.z) for e in bad]


def test_false_loop_closures_need_room() -> None:
    poses, edges = pg.simulate(1, 10, 0)
    with pytest.raises(ValueError):
        rb.false_loop_closures(poses, edges, 1, 0, min_gap=10)


@FAST
@given(st.floats(-50, 50), st.floats(-50, 50), st.floats(-math.pi, math.pi))
def test_position_error_is_gauge_free(tx: float, ty: float, angle: float) -> None:
    poses, _ = pg.simulate(2, 9, 0)
    c, s = math.cos(angle), math.sin(angle)
    moved = poses.copy()
    moved[:, 0] = c * poses[:, 0] - s * poses[:, 1] + tx
    moved[:, 1] = s * poses[:, 0] + c * poses[:, 1] + ty
    moved[:, 2] = poses[:, 2] + angle
    assert rb.position_error(poses, moved) == pytest.approx(0.0, abs=1e-9)


def test_loop_closures_are_decided_by_the_ids() -> None:
    info = np.eye(3)
    edges = [pg.Edge(0, 1, (1, 0, 0), info), pg.Edge(2, 1, (1, 0, 0), info)]
    edges += [pg.Edge(0, 2, (1, 0, 0), info), pg.Edge(3, 0, (1, 0, 0), info)]
    assert rb.loop_closures(edges).tolist() == [False, False, True, True]


# --- robust/levenberg-marquardt's reference ---------------------------------------------------


def _reference() -> object:
    import importlib.util
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "exercises" / "robust" / "reference.py"
    spec = importlib.util.spec_from_file_location("_ref_robust_unit", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


REF: object = _reference()


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2**31), st.integers(3, 10), st.sampled_from([0.6, 1.2]))
def test_dense_mistake_free_trials_equal_the_sparse_optimiser(
    seed: int, n: int, drift: float
) -> None:
    """The dense loop the mutants are built on (no switch on) is the module's optimiser."""
    poses, edges = REF.drifted_graph(seed, n, 2, drift)  # type: ignore[attr-defined]
    plain = REF._plain(edges)  # type: ignore[attr-defined]
    for lam0 in (1e-6, 1.0, 1e4):
        dense, _ = REF._lm_trials(poses.tolist(), plain, lam0, 8)  # type: ignore[attr-defined]
        sparse, _, _ = rb.levenberg_marquardt(poses, edges, 8, lam0)
        assert np.allclose(pg.relative_to_first(dense), pg.relative_to_first(sparse), atol=1e-9)


def test_lm_limits_tiny_lambda_is_gauss_newton_and_huge_is_a_gradient_step() -> None:
    poses, edges = REF.drifted_graph(11, 5, 1, 0.3)  # type: ignore[attr-defined]
    plain = REF._plain(edges)  # type: ignore[attr-defined]
    one = REF.levenberg_marquardt(poses.tolist(), plain, 1e-9, 1)  # type: ignore[attr-defined]
    gn = pg.relative_to_first(pg.gauss_newton_step(poses, edges))
    assert np.allclose(one, gn, atol=1e-6)
    # λ = 10⁴: Δ ≈ −diag(H)⁻¹ b / λ, a scaled gradient step
    h, b = pg.linear_system(poses, edges)
    lam = 1e4
    step = -b[3:] / (lam * np.diag(h)[3:])
    y = poses.copy()
    y[1:] += step.reshape(-1, 3)
    got = REF.levenberg_marquardt(poses.tolist(), plain, lam, 1)  # type: ignore[attr-defined]
    assert np.allclose(got, pg.relative_to_first(y), atol=1e-6)
    assert pg.chi2(y, edges) < pg.chi2(poses, edges)


def test_lm_rejected_trial_returns_the_initial_guess_and_zero_trials_too() -> None:
    poses, edges = REF.drifted_graph(4, 6, 2, 0.9)  # type: ignore[attr-defined]
    plain = REF._plain(edges)  # type: ignore[attr-defined]
    record = REF.lm_record(poses.tolist(), plain, 1e-6, 6)  # type: ignore[attr-defined]
    assert [rho < 0 for _, rho, _ in record] == [True] * 5 + [False]
    assert [lam for lam, _, _ in record] == pytest.approx(
        [1e-6 * f for f in (1, 2, 8, 64, 1024, 32768)]
    )
    start = pg.relative_to_first(poses)
    for trials in (0, 1, 5):
        got = REF.levenberg_marquardt(poses.tolist(), plain, 1e-6, trials)  # type: ignore[attr-defined]
        assert np.array_equal(got, start)
    assert not np.allclose(REF.levenberg_marquardt(poses.tolist(), plain, 1e-6, 6), start)  # type: ignore[attr-defined]


def test_lm_valid_states_the_domain() -> None:
    poses, edges = REF.drifted_graph(4, 6, 2, 0.9)  # type: ignore[attr-defined]
    p, e = poses.tolist(), REF._plain(edges)  # type: ignore[attr-defined]
    valid = REF.lm_valid  # type: ignore[attr-defined]
    assert valid(p, e, 1e-6, 8)
    assert not valid(p, e, 0.0, 8) and not valid(p, e, 1e-6, 16)
    assert not valid(p, e[1:], 1e-6, 8)  # pose 0 cut off from the rest
    assert not valid(p, [[0, 0, [0, 0, 0], np.eye(3).tolist()], *e], 1e-6, 8)
    bad = [[*x[:3], (-np.eye(3)).tolist()] if k == 0 else x for k, x in enumerate(e)]
    assert not valid(p, bad, 1e-6, 8)
