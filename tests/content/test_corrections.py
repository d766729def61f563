"""Issue 16: corrections to chapters 1–18, each pinned against an independent computation.

Every figure the corrected prose quotes is recomputed here by another method (a brute force, a
Monte-Carlo run, scipy, exact fractions); every claim the issue found wrong is checked to be
gone; and every code prompt must state its tolerance and its allowed imports.
"""

from __future__ import annotations

import importlib.util
import math
import re
from collections.abc import Callable
from fractions import Fraction
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest
import yaml

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.course.variants import variant

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = ROOT / "chapters"
COURSE = load_course(bundled_course_root())


def chapter(prefix: str) -> str:
    (path,) = CHAPTERS.glob(f"{prefix}-*.md")
    return " ".join(path.read_text(encoding="utf-8").split())


def exercise_text(ex_id: str) -> str:
    path = ROOT / "exercises" / f"{ex_id}.yaml"
    return " ".join(path.read_text(encoding="utf-8").split())


def load_reference(chapter_id: str) -> ModuleType:
    path = ROOT / "exercises" / chapter_id / "reference.py"
    name = f"_ref_corrections_{chapter_id.replace('-', '_')}"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --- 1. chapter 5: the only prior's pose sits at the prior's mean -----------------------------


def _loop_system(
    prior: float, m: float, d01: float, d12: float, d02: float
) -> tuple[list[list[Fraction]], list[Fraction]]:
    """Ω and ξ of the 3-pose loop built from the measurements, with exact fractions."""
    f = [Fraction(v).limit_denominator(10**6) for v in (prior, m, d01, d12, d02)]
    prior_, m_, a, b, c = f
    one = Fraction(1)
    omega = [[prior_ + 2, -one, -one], [-one, 2 * one, -one], [-one, -one, 2 * one]]
    xi = [prior_ * m_ - a - c, a - b, b + c]
    return omega, xi


def _solve_fractions(omega: list[list[Fraction]], xi: list[Fraction]) -> list[Fraction]:
    """Gauss-Jordan elimination in exact fractions (independent of numpy and the reference)."""
    n = len(xi)
    a = [[Fraction(v) for v in row] + [Fraction(xi[i])] for i, row in enumerate(omega)]
    for col in range(n):
        piv = next(r for r in range(col, n) if a[r][col] != 0)
        a[col], a[piv] = a[piv], a[col]
        a[col] = [v / a[col][col] for v in a[col]]
        for r in range(n):
            if r != col:
                a[r] = [vr - a[r][col] * vc for vr, vc in zip(a[r], a[col], strict=True)]
    return [row[-1] for row in a]


def test_loop_xi_comes_from_the_stated_measurements() -> None:
    omega, xi = _loop_system(10, 1.4, 2, 1, 2)
    assert xi == [10, 1, 3]
    mu = _solve_fractions(omega, xi)
    assert mu == [Fraction(7, 5), Fraction(46, 15), Fraction(56, 15)]
    # the loop's 1 m of disagreement shared equally: 2 − 1/3, 1 − 1/3, 2 + 1/3
    assert mu[1] - mu[0] == 2 - Fraction(1, 3)
    assert mu[2] - mu[1] == 1 - Fraction(1, 3)
    assert mu[2] - mu[0] == 2 + Fraction(1, 3)
    assert _solve_fractions(omega, xi) != [Fraction(7, 5), 2, Fraction(13, 5)]
    text = chapter("05")
    for quoted in ("46/15", "56/15", "[12.2, 0, 1.8]", "10/12 \\approx 0.83"):
        assert quoted in text


@pytest.mark.parametrize("prior", [0.5, 10, 1000])
@pytest.mark.parametrize("measures", [(2, 1, 2), (0.3, 4.1, -2.0), (7, 7, 0.5)])
def test_single_prior_pose_is_the_prior_mean(prior: float, measures: tuple[float, ...]) -> None:
    """Whatever the edges and however strong the prior: μ₀ = the prior's mean."""
    omega, xi = _loop_system(prior, -3.7, *measures)
    assert _solve_fractions(omega, xi)[0] == Fraction(-37, 10)


def test_graph_exercises_answer_the_prior_mean_for_every_variant() -> None:
    graph = load_reference("graph")
    for ex_id in ("graph/solve-first", "graph/solve-estimate"):
        spec = COURSE.exercise(ex_id)
        for seed in range(0, 12):
            p = variant(spec, seed).params
            _, xi = _loop_system(p["prior"], p["m"], p["d01"], p["d12"], p["d02"])
            assert [float(v) for v in xi] == pytest.approx([p["xi0"], p["xi1"], p["xi2"]])
            mu0 = graph.loop_first_estimate(**p)
            assert mu0 == pytest.approx(p["m"], abs=1e-9)


def test_no_edge_pulls_the_anchored_pose() -> None:
    for text in (
        chapter("05"),
        exercise_text("graph/solve-first"),
        exercise_text("graph/solve-estimate"),
        exercise_text("graph/solve-information"),
    ):
        assert "pull it away" not in text and "pull on $x_0$" not in text
        assert "placed by the whole graph" not in text
        assert "matter even for a pose with a strong prior" not in text


# --- 2. essential matrices: 6-dimensional, 5 up to scale ---------------------------------------


def _skew(t: np.ndarray) -> np.ndarray:
    return np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])


def _rot(w: np.ndarray) -> np.ndarray:
    from scipy.spatial.transform import Rotation  # type: ignore[import-untyped]

    return np.asarray(Rotation.from_rotvec(w).as_matrix())


def test_essential_set_is_six_dimensional() -> None:
    """The rank of the Jacobian of (t, ω) ↦ [t]× R(ω), by central differences, is 6."""
    rng = np.random.default_rng(3)
    t0, w0 = rng.normal(size=3), rng.normal(size=3) * 0.5
    h = 1e-6
    cols = []
    for k in range(6):
        d = np.zeros(6)
        d[k] = h
        plus = _skew(t0 + d[:3]) @ _rot(w0 + d[3:])
        minus = _skew(t0 - d[:3]) @ _rot(w0 - d[3:])
        cols.append(((plus - minus) / (2 * h)).ravel())
    s = np.linalg.svd(np.array(cols).T, compute_uv=False)
    assert int(np.sum(s > 1e-6 * s[0])) == 6
    text = exercise_text("vision/essential-dof")
    assert "5-dimensional surface" not in text and "6-dimensional" in text


# --- 3. chapter 1: a new landmark is born correlated ------------------------------------------


def test_new_landmark_is_born_correlated() -> None:
    """Augmenting a state whose pose is uncertain gives a nonzero cross-covariance G_r P_r·."""
    from slamcourse.slam import ekfslam

    mu = np.array([1.0, 2.0, 0.3, 5.0, 5.0])
    p = np.diag([0.04, 0.04, 0.01, 0.1, 0.1])
    p[0, 3] = p[3, 0] = 0.02  # the pose already correlated with landmark 1
    _, p2 = ekfslam.augment(mu, p, [4.0, 0.5], np.diag([0.01, 0.001]))
    assert np.abs(p2[5:7, :3]).max() > 1e-3  # with the pose
    assert np.abs(p2[5:7, 3:5]).max() > 1e-3  # and, through it, with the old landmark
    assert "starts out uncorrelated" not in chapter("01")


# --- 4. chapter 3: whitening with a Cholesky factor --------------------------------------------


def test_correlated_mahalanobis_example() -> None:
    nu = np.array([0.3, -0.09])
    s = np.array([[0.25, 0.03], [0.03, 0.01]])
    diagonal = float(np.sum(nu**2 / np.diag(s)))
    full = float(nu @ np.linalg.solve(s, nu))
    low = np.linalg.cholesky(s)
    w = np.linalg.solve(low, nu)
    assert diagonal == pytest.approx(1.17)
    assert full == pytest.approx(2.840625)
    assert low == pytest.approx(np.array([[0.5, 0], [0.06, 0.08]]))
    assert w == pytest.approx([0.6, -1.575])
    assert float(w @ w) == pytest.approx(full)
    # whitened innovations are standard normal and independent (Monte Carlo)
    rng = np.random.default_rng(0)
    samples = rng.multivariate_normal([0, 0], s, size=200_000)
    white = np.linalg.solve(low, samples.T).T
    assert np.cov(white.T) == pytest.approx(np.eye(2), abs=0.02)
    text = chapter("03")
    quotes = ("S = H \\Sigma H^T + R", "d^2 = \\nu^T S^{-1} \\nu = 2.84", "w = [0.6, -1.575]^T")
    for quoted in quotes:
        assert quoted in text


# --- 5. chapter 4: which heading errors cancel on a loop ---------------------------------------


def _square(heading_error: Callable[[int], float], side: int = 100, step: float = 0.5) -> float:
    """End point of a believed square loop whose heading at step k is off by heading_error(k)."""
    pos = np.zeros(2)
    k = 0
    for corner in range(4):
        for _ in range(side):
            a = corner * math.pi / 2 + heading_error(k)
            pos = pos + step * np.array([math.cos(a), math.sin(a)])
            k += 1
    return float(np.hypot(*pos))


def test_heading_errors_on_a_closed_loop() -> None:
    assert _square(lambda k: 0.05) == pytest.approx(0, abs=1e-9)  # constant offset cancels
    assert _square(lambda k: 1e-4 * k) > 1  # gyro bias does not
    delta = 0.05
    jump = _square(lambda k: delta if k >= 150 else 0.0)  # jump half-way along side 2
    jump_point = np.array([50.0, 25.0])
    assert jump == pytest.approx(2 * math.sin(delta / 2) * np.hypot(*jump_point))
    text = chapter("04")
    assert "nothing cancels" not in text and "a heading error never does" not in text
    assert "as the next exercise shows" not in exercise_text("drift/square-loop")


# --- 6. chapter 9: odometry noise as variance per metre ----------------------------------------


def test_rate_model_depends_on_the_step_size() -> None:
    def after_50m(step: float) -> float:
        return 0.5 * step * math.sqrt(50 / step)  # degrees, σ ∝ step, steps added in variance

    assert after_50m(0.1) == pytest.approx(1.118, abs=1e-3)
    assert after_50m(5) == pytest.approx(7.906, abs=1e-3)
    text = chapter("09")
    assert "1.1°" in text and "7.9°" in text and "The position error stays modest" not in text


def test_variance_per_metre_is_independent_of_the_step() -> None:
    capstone = load_reference("capstone")
    totals = []
    for step in (0.1, 0.5, 2.0):
        pos, theta = capstone.odometry_step(
            step=step, calibration=2, sigma_dist_cm=1, sigma_heading_deg=0.5
        )
        n = round(50 / step)
        totals.append((math.sqrt(n) * pos, math.sqrt(n) * theta))
    assert np.allclose(totals, totals[0])
    assert capstone.odometry_step(
        step=0.5, calibration=2, sigma_dist_cm=1, sigma_heading_deg=0.5
    ) == pytest.approx([0.005, math.radians(0.25)])


def test_heading_random_walk_lateral_error() -> None:
    sigma, step, n = 0.00436, 0.5, 100
    closed = step * sigma * math.sqrt(sum(k * k for k in range(1, n + 1)))
    rng = np.random.default_rng(1)
    headings = np.cumsum(rng.normal(0, sigma, size=(20_000, n)), axis=1)
    lateral = step * np.sin(headings).sum(axis=1)
    assert closed == pytest.approx(1.27, abs=0.005)
    assert float(lateral.std()) == pytest.approx(closed, rel=0.03)
    assert "1.27" in chapter("09") and "338350" in chapter("09")


# --- 7. log-odds: unclamped updates undo, clamped ones depend on order -------------------------


def _clamped(seq: list[float], lo: float = -2.0, hi: float = 3.5) -> float:
    value = 0.0
    for step in seq:
        value = min(hi, max(lo, value + step))
    return value


def test_clamping_makes_order_matter() -> None:
    hits, misses = [0.85] * 5, [-0.4] * 5
    assert _clamped(hits + misses) == pytest.approx(1.5)
    assert _clamped(misses + hits) == pytest.approx(2.25)
    assert sum(hits + misses) == pytest.approx(2.25)
    # unclamped: subtracting undoes exactly; clamped: it does not
    assert _clamped([0.85] * 5 + [-0.85] * 5, lo=-99, hi=99) == pytest.approx(0)
    assert _clamped([0.85] * 5 + [-0.85] * 5) != pytest.approx(0)
    assert "1.5" in chapter("15") and "2.25" in chapter("15")
    assert "cannot simply be taken back." not in chapter("09")
    assert "log-odds updates cannot simply be taken back." not in exercise_text(
        "capstone/frame-pipeline"
    )


# --- 8. chapter 6: linear equations in E, the (R, t) convention, one global scale --------------


def test_epipolar_equation_is_linear_in_e_and_convention() -> None:
    vision = load_reference("vision")
    rng = np.random.default_rng(2)
    r, t = _rot(rng.normal(size=3) * 0.2), rng.normal(size=3)
    e = np.asarray(vision.essential_matrix(t.tolist(), r.tolist()))
    x1 = np.array([0.1, -0.2, 1.0]) * 4.0  # a point in the first camera's frame
    x2 = r @ x1 + t  # the convention the chapter states
    a, b = x1 / x1[2], x2 / x2[2]
    assert float(b @ e @ a) == pytest.approx(0, abs=1e-12)
    # one equation per correspondence, linear in the nine entries: kron(x', x) · vec(E) = 0
    assert float(np.kron(b, a) @ e.ravel()) == pytest.approx(0, abs=1e-12)
    # the polynomial constraints every essential matrix meets
    assert np.allclose(2 * e @ e.T @ e - np.trace(e @ e.T) * e, 0, atol=1e-12)
    text = chapter("06")
    assert "X_2 = R X_1 + t" in text and "one global scale" in text.replace("**", "")
    assert "visual odometry from one camera gives the direction of travel only" not in text


# --- 9. chapter 14: one scan's d² values are correlated through the pose -----------------------


def test_scan_nis_values_are_correlated() -> None:
    from slamcourse.slam import jcbb as jc

    ref = load_reference("jcbb")
    _, h = jc.stack(np.array(ref.SCENE_MU), ref.scene_measurements(), (0, 1))
    s = h @ ref.SCENE_P @ h.T + np.kron(np.eye(2), ref.SCENE_R)
    a = np.zeros((4, 4))
    a[:2, :2], a[2:, 2:] = np.linalg.inv(s[:2, :2]), np.linalg.inv(s[2:, 2:])
    closed = 2 * float(np.trace(a @ s @ a @ s))  # Var(νᵀAν) of a Gaussian quadratic form
    rng = np.random.default_rng(4)
    v = rng.multivariate_normal(np.zeros(4), s, size=200_000)
    q = np.einsum("ki,ij,kj->k", v, a, v)
    assert closed == pytest.approx(11.9, abs=0.05)
    assert float(q.var()) == pytest.approx(closed, rel=0.03)
    assert float(q.mean()) == pytest.approx(4, rel=0.02)
    assert "about 11.9" in chapter("14")


# --- 10. chapters 11, 12, 15, 16, 18 ---------------------------------------------------------


def test_intel_conventions_and_strongest_edges() -> None:
    from slamcourse.slam import posegraph as pg

    intel = load_reference("intel")
    graph = intel.intel()
    strong = [e for e in graph.edges if np.linalg.eigvalsh(e.information).max() > 1e6]
    assert len(strong) == 196 and all(abs(e.i - e.j) == 1 for e in strong)
    x1, _ = pg.gauss_newton(graph.poses, graph.edges, 10)
    x2, _ = pg.gauss_newton(graph.poses, graph.edges, 10, model=intel.inverse_convention)
    r1, r2 = pg.relative_to_first(x1), pg.relative_to_first(x2)
    moved = float(np.hypot(*(r1[:, :2] - r2[:, :2]).T).max())
    assert 0.02 < moved < 0.0235
    assert 26 <= float(np.ptp(r1[:, 0])) < 27
    text = chapter("18")
    assert "visibly different" not in text and "2.3 cm" in text and "all 196 edges" in text


def test_correlated_update_drop() -> None:
    pxx, pyy, pxy, r = 0.04, 0.09, 0.03, 0.02
    p = np.array([[pxx, pxy], [pxy, pyy]])
    h = np.array([[1.0, 0.0]])
    k = p @ h.T / (pxx + r)
    after = (np.eye(2) - k @ h) @ p
    assert pyy - after[1, 1] == pytest.approx(pxy**2 / (pxx + r))
    assert "exactly as much as the two were correlated" not in chapter("12")
    assert "P_{xy}^2 / (P_{xx} + R)" in chapter("12")


def test_central_difference_is_rounding_limited_at_1e_6() -> None:
    def f(x: float) -> float:
        return math.sin(3 * x) * 2.0

    x, exact = 0.7, 6 * math.cos(2.1)
    errors = {h: abs((f(x + h) - f(x - h)) / (2 * h) - exact) for h in (1e-3, 1e-6)}
    truncation_1e6 = 54 * 1e-12 / 6  # |f'''| h² / 6 at h = 1e-6
    assert errors[1e-3] == pytest.approx(54 * math.cos(2.1) * 1e-6 / 6 * -1, rel=0.01)
    assert errors[1e-6] > 10 * truncation_1e6  # rounding, not h², dominates
    assert errors[1e-6] < 1e-9
    assert "rounding dominates" in chapter("11")


def _exact_traversal(x0: int, y0: int, x1: int, y1: int) -> set[tuple[int, int]]:
    """Cells whose unit square the segment between the two cell centres passes through
    (dense sampling; exact for segments that meet no grid corner)."""
    cells = set()
    for s in np.linspace(0, 1, 20001):
        cells.add((round(x0 + s * (x1 - x0)), round(y0 + s * (y1 - y0))))
    return cells


def test_bresenham_is_thinner_than_the_exact_traversal() -> None:
    scan = load_reference("scan-matching")
    line = scan.bresenham(0, 0, 4, 2)
    assert len(line) == 5 and len(_exact_traversal(0, 0, 4, 2)) == 7 == 4 + 2 + 1
    assert {tuple(c) for c in line} < _exact_traversal(0, 0, 4, 2)
    text = chapter("15")
    assert "Amanatides" in text and "which cells a beam crosses" not in text


def test_isam2_described_right() -> None:
    text = chapter("16")
    assert "relinearises only the variables a new measurement touches" not in text
    assert "up to the root" in text and "threshold" in text
    assert "re-eliminates only the variables that a new factor touches" not in chapter("09")


def test_gauge_fix_damping_option_is_judged_on_a_condition_it_fails() -> None:
    data = yaml.safe_load((ROOT / "exercises/pose-graph/gauge-fix.yaml").read_text())
    assert "undamped Gauss-Newton step" in data["prompt"]
    e = next(c for c in data["choices"] if "lambda I" in c["text"])
    assert not e.get("correct")


# --- one course --------------------------------------------------------------------------------


def test_orderings_no_longer_duplicates_the_star() -> None:
    assert not (ROOT / "exercises/orderings/star-hub-first.yaml").exists()
    orderings = load_reference("orderings")
    # brute force: the pose pairs a landmark joins, minus those odometry already joined
    for poses, landmarks in ((5, 40), (3, 15), (12, 200)):
        expected = math.comb(poses, 2) - (poses - 1)
        assert orderings.landmarks_first(poses, landmarks) == expected
        assert orderings.mistake_landmarks_first_poses_first(poses, landmarks) == math.comb(
            landmarks, 2
        )
    text = chapter("16")
    assert "Chapter 7" in text and "Schur complement" in text


def test_forward_introductions() -> None:
    c15, c16 = chapter("15"), chapter("16")
    assert c15.index("INTEL") == c15.index("optimises INTEL") + len("optimises ")
    assert c16.index("J^\\top \\Omega J") > c16.index("**Gauss-Newton**")
    assert c16.index("**INTEL**") < c16.index("On INTEL")


def test_notation_page() -> None:
    ids = [c.id for c in COURSE.chapters]
    assert ids[-1] == "notation" and not COURSE.chapter("notation").exercises
    assert "notation" in ids
    text = chapter("99")
    for symbol in ("\\mu", "\\Sigma", "P", "\\Omega", "H", "K", "\\sigma", "p", "z"):
        assert f"${symbol}" in text


# --- every code prompt names its tolerance and its imports -------------------------------------


CODE = [
    ex_id
    for ex_id in COURSE.exercise_ids
    if "kind: code" in COURSE.exercise_path(ex_id).read_text(encoding="utf-8")
]


@pytest.mark.parametrize("ex_id", CODE)
def test_code_prompt_states_tolerance_and_imports(ex_id: str) -> None:
    spec = COURSE.exercise(ex_id)
    prompt = " ".join(spec.prompt.source.split())
    rule = r"toleran|compared within|accepted within|accurate to|must be exact"
    said = re.search(rule, prompt, re.I)
    assert said, f"{spec.id}: the prompt states no tolerance"
    assert re.search(r"\bimport", prompt, re.I), f"{spec.id}: the prompt names no imports"
    assert "numpy" in prompt, f"{spec.id}: the prompt does not say numpy may be imported"


def test_nees_hint_keeps_the_prompt_interval() -> None:
    data = yaml.safe_load((ROOT / "exercises/consistency/nees.yaml").read_text())
    hint = data["hints"][0]
    assert "(-\\pi, \\pi]" in hint and "turn that into $\\pi$" in hint
