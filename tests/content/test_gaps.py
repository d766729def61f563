"""The teaching gaps of chapters 5, 6, 8, 12 and 13 (issue 16): their references against
independent computations, and every figure the new prose quotes.

The new code exercises' solutions, starters, mutants and variants are graded, like every code
exercise's, by the course's validation (``test_bundled_course.py::test_exercise_is_sound``);
they are not graded a second time here.
"""

from __future__ import annotations

import importlib.util
import itertools
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.spatial.transform import Rotation  # type: ignore[import-untyped]
from scipy.stats import chi2  # type: ignore[import-untyped]

ROOT = Path(__file__).resolve().parents[2]
FAST = settings(max_examples=60, deadline=None, suppress_health_check=list(HealthCheck))


def load_reference(chapter: str) -> ModuleType:
    path = ROOT / "exercises" / chapter / "reference.py"
    spec = importlib.util.spec_from_file_location(f"_ref_gaps_{chapter.replace('-', '_')}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


graph = load_reference("graph")
vision = load_reference("vision")
occupancy = load_reference("occupancy")
ekf_slam = load_reference("ekf-slam")
jcbb = load_reference("jcbb")


def chapter(name: str) -> str:
    return (ROOT / "chapters" / name).read_text(encoding="utf-8")


# --- chapter 5: one edge expanded ---------------------------------------------------------------


def _edge_cost(i: int, j: int, w: float, d: float, x: np.ndarray) -> float:
    return float(w * (x[j] - x[i] - d) ** 2)


@pytest.mark.parametrize(("i", "j", "w", "d"), [(1, 3, 4, 2.5), (3, 0, 2, -1.5), (0, 1, 9, 0.7)])
def test_edge_contributions_are_half_the_hessian_and_minus_half_the_gradient(
    i: int, j: int, w: float, d: float
) -> None:
    # independent: central differences of the cost itself (exact for a quadratic)
    h = 1e-3
    hess = np.zeros((4, 4))
    for a, b in itertools.product(range(4), repeat=2):
        ea, eb = np.eye(4)[a] * h, np.eye(4)[b] * h
        hess[a, b] = (
            _edge_cost(i, j, w, d, ea + eb)
            - _edge_cost(i, j, w, d, ea - eb)
            - _edge_cost(i, j, w, d, -ea + eb)
            + _edge_cost(i, j, w, d, -ea - eb)
        ) / (4 * h * h)
    grad0 = np.array(
        [
            (_edge_cost(i, j, w, d, np.eye(4)[a] * h) - _edge_cost(i, j, w, d, -np.eye(4)[a] * h))
            / (2 * h)
            for a in range(4)
        ]
    )
    assert np.allclose(graph.edge_omega(i, j, w, d), hess / 2, atol=1e-6)
    assert np.allclose(graph.edge_xi(i, j, w, d), -grad0 / 2, atol=1e-6)
    assert np.allclose(graph.edge_cost_gradient(i, j, w, d, [0, 0, 0, 0]), grad0, atol=1e-6)


def test_edge_reversed_adds_the_same_and_states_its_measurement() -> None:
    # the prose: stored as (j, i, -d) the edge adds the same entries; Ω_e μ = ξ_e is the measurement
    assert graph.edge_omega(1, 3, 4, 2.5) == graph.edge_omega(3, 1, 4, -2.5)
    assert graph.edge_xi(1, 3, 4, 2.5) == graph.edge_xi(3, 1, 4, -2.5)
    x = np.array([0.3, 1.0, -2.0, 3.5])  # x_3 − x_1 = 2.5: the edge is satisfied
    assert np.allclose(np.array(graph.edge_omega(1, 3, 4, 2.5)) @ x, graph.edge_xi(1, 3, 4, 2.5))


# --- chapter 6: E back to R and t, Hartley --------------------------------------------------


def _dlt_depths(R: np.ndarray, t: np.ndarray, x1: np.ndarray, x2: np.ndarray) -> tuple[float, ...]:
    """Independent triangulation: the homogeneous point as the null vector of the DLT system."""
    p1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    p2 = np.hstack([R, t.reshape(3, 1)])
    a = np.array([x1[0] * p1[2] - p1[0], x1[1] * p1[2] - p1[1],
                  x2[0] * p2[2] - p2[0], x2[1] * p2[2] - p2[1]])  # fmt: skip
    hom = np.linalg.svd(a)[2][-1]
    point = hom[:3] / hom[3]
    return float(point[2]), float((R @ point + t)[2])


def test_sideways_step_depth_pairs_quoted_in_the_chapter() -> None:
    text = chapter("06-vision.md")
    assert "$(1, 1)$, $(-1, -1)$, $(1, -1)$ and $(-1, 1)$" in text
    e = np.array([[0.0, 0, 0], [0, 0, -1], [0, 1, 0]])
    x1, x2 = np.array([0.0, 0, 1]), np.array([1.0, 0, 1])
    pairs = {tuple(round(v) for v in _dlt_depths(r, t, x1, x2))
             for r, t in vision.essential_candidates(e)}  # fmt: skip
    assert pairs == {(1, 1), (-1, -1), (1, -1), (-1, 1)}
    assert np.allclose(
        vision.decompose_essential(e, x1, x2), np.hstack([np.eye(3), [[1], [0], [0]]])
    )


@FAST
@given(
    st.integers(0, 2**32 - 1),
    st.floats(0.0, 0.6),
    st.floats(0.2, 5.0),
    st.sampled_from([1.0, -1.0]),
)
def test_decompose_recovers_the_true_motion(
    seed: int, angle: float, scale: float, sign: float
) -> None:
    rng = np.random.default_rng(seed)
    r = Rotation.from_rotvec(angle * _unit(rng.normal(size=3))).as_matrix()
    t = _unit(rng.normal(size=3)) * rng.uniform(0.2, 2.0)
    depth = rng.uniform(2.0, 20.0)
    p1 = np.array([rng.uniform(-0.5, 0.5) * depth, rng.uniform(-0.4, 0.4) * depth, depth])
    p2 = r @ p1 + t
    e = sign * scale * np.cross(np.eye(3), t) @ r  # [t]× R, built by crossing t with the axes
    kw = {"E": e.tolist(), "x1": (p1 / p1[2]).tolist(), "x2": (p2 / p2[2]).tolist()}
    if not vision.decompose_valid(**kw):
        return
    got = vision.decompose_essential(**kw)
    assert np.allclose(got[:, :3], r, atol=1e-8)
    assert np.allclose(got[:, 3], t / np.linalg.norm(t), atol=1e-8)


def _unit(v: np.ndarray) -> np.ndarray:
    return np.asarray(v / np.linalg.norm(v))


def test_skew_from_cross_is_the_reference_skew() -> None:
    t = np.array([0.3, -1.2, 2.0])
    assert np.allclose(np.cross(np.eye(3), t), vision.skew(t))


@pytest.mark.parametrize(
    "pts", [(40, 60, 600, 90, 560, 420, 300, 250), (0, 0, 640, 480, 320, 10, 100, 400)]
)
def test_hartley_transform_centres_and_scales(pts: tuple[int, ...]) -> None:
    t = np.array(vision.hartley_matrix(*pts))
    homogeneous = np.column_stack([np.reshape(pts, (4, 2)), np.ones(4)])
    out = (t @ homogeneous.T).T
    assert np.allclose(out[:, 2], 1)
    assert np.allclose(out[:, :2].mean(axis=0), 0, atol=1e-12)
    assert np.mean(np.hypot(out[:, 0], out[:, 1])) == pytest.approx(math.sqrt(2))


def test_pixel_products_quoted_in_the_chapter() -> None:
    assert "$640^2 \\approx 4 \\times 10^5$" in chapter("06-vision.md")
    assert pytest.approx(4e5, rel=0.05) == 640**2


# --- chapter 8: a prior other than one half -----------------------------------------------


@pytest.mark.parametrize("p0", [0.1, 0.2, 0.3, 0.7, 0.8])
@pytest.mark.parametrize(("p1", "p2"), [(0.9, 0.3), (0.6, 0.7), (0.95, 0.2)])
def test_prior_update_matches_bayes_on_probabilities(p0: float, p1: float, p2: float) -> None:
    # independent: Bayes' rule on a two-state cell with likelihoods implied by the sensor model
    like = [(p / p0, (1 - p) / (1 - p0)) for p in (p1, p2)]  # p(z|m) ∝ p(m|z)/p(m)
    occupied, free = p0, 1 - p0
    for lm, lf in like:
        occupied, free = occupied * lm, free * lf
    want = occupied / (occupied + free)
    got = occupancy.prior_update(p0, p1, p2)
    assert got[1] == pytest.approx(want, rel=1e-12)
    assert got[0] == pytest.approx(math.log(want / (1 - want)), rel=1e-9)
    assert occupancy.prior_update_bayes(p0, p1, p2) == pytest.approx(want, rel=1e-12)


def test_prior_figures_quoted_in_the_chapter() -> None:
    text = chapter("08-occupancy.md")
    l0 = math.log(0.2 / 0.8)
    assert f"$l_0 = {l0:.3f}$" in text
    assert math.log(0.9 / 0.1) == pytest.approx(2.197, abs=5e-4)
    # one reading of 0.9 must leave the cell at 0.9 exactly (odds arithmetic, no logarithm)
    assert occupancy.prior_update(0.2, 0.9, 0.2)[1] == pytest.approx(0.9)
    wrong = l0 + math.log(9)
    assert f"{wrong:.3f}" == "0.811" and "0.811" in text
    assert f"{1 / (1 + math.exp(-wrong)):.2f}" == "0.69" and "0.69" in text
    # ten readings that say nothing, each adding l0 again: odds (1/4)^11
    odds = 0.25**11
    assert f"{odds / (1 + odds):.1e}" == "2.4e-07"
    assert "2.4 \\times 10^{-7}" in text


# --- chapter 12: the whole step -----------------------------------------------------------


def _independent_step(
    mu: list[float], sigma: Any, u: list[float], m: Any, z: Any, ids: list[int], r: Any
) -> np.ndarray:
    """The step from the textbook matrices: full F, and the update in information form."""
    x = np.array(mu, dtype=float)
    p = np.array(sigma, dtype=float)
    n = x.size
    a = x[2] + u[0]
    f = np.eye(n)
    f[0, 2], f[1, 2] = -u[1] * math.sin(a), u[1] * math.cos(a)
    v = np.zeros((n, 3))
    v[:3] = np.array(
        [[-u[1] * math.sin(a), math.cos(a), 0], [u[1] * math.cos(a), math.sin(a), 0], [1, 0, 1]]
    )
    x[:3] += [u[1] * math.cos(a), u[1] * math.sin(a), u[0] + u[2]]
    p = f @ p @ f.T + v @ np.asarray(m) @ v.T
    rm = np.asarray(r, dtype=float)
    for zk, j in zip(z, ids, strict=True):
        n = x.size
        if 3 + 2 * j < n:
            dx, dy = x[3 + 2 * j] - x[0], x[4 + 2 * j] - x[1]
            q = dx * dx + dy * dy
            h = np.zeros((2, n))
            h[0, [0, 1, 3 + 2 * j, 4 + 2 * j]] = np.array([-dx, -dy, dx, dy]) / math.sqrt(q)
            h[1, [0, 1, 2, 3 + 2 * j, 4 + 2 * j]] = [dy / q, -dx / q, -1, -dy / q, dx / q]
            b = zk[1] - math.atan2(dy, dx) + x[2]
            nu = np.array([zk[0] - math.sqrt(q), math.atan2(math.sin(b), math.cos(b))])
            post = np.linalg.inv(np.linalg.inv(p) + h.T @ np.linalg.inv(rm) @ h)
            x = x + post @ h.T @ np.linalg.inv(rm) @ nu
            p = post
        else:
            rr, phi = zk
            c = x[2] + phi
            jac = np.zeros((n + 2, n + 2))
            jac[:n, :n] = np.eye(n)
            jac[n:, :3] = [[1, 0, -rr * math.sin(c)], [0, 1, rr * math.cos(c)]]
            jac[n:, n:] = [[math.cos(c), -rr * math.sin(c)], [math.sin(c), rr * math.cos(c)]]
            joint = np.zeros((n + 2, n + 2))
            joint[:n, :n], joint[n:, n:] = p, rm
            p = jac @ joint @ jac.T
            x = np.append(x, [x[0] + rr * math.cos(c), x[1] + rr * math.sin(c)])
    return np.vstack([x, p])


@FAST
@given(ekf_slam.ekf_step_inputs())
def test_ekf_slam_step_matches_the_textbook_matrices(kw: dict[str, Any]) -> None:
    if not ekf_slam.ekf_step_valid(**kw):
        return
    got = ekf_slam.ekf_slam_step(**kw)
    want = _independent_step(**{k: kw[k] for k in ("mu", "u", "z", "ids")},
                             sigma=kw["Sigma"], m=kw["M"], r=kw["R"])  # fmt: skip
    diff = got - want
    diff[0, 2] = math.remainder(diff[0, 2], 2 * math.pi)  # the reference wraps the heading
    assert np.allclose(diff, 0, rtol=0, atol=1e-7 * (1 + np.abs(want).max()))


def test_state_size_quoted_in_the_chapter() -> None:
    text = chapter("12-ekf-slam.md")
    n = 3 + 2 * 1000
    assert "the\nstate has 2003 entries" in text or "state has 2003 entries" in text
    assert n == 2003 and n * n == pytest.approx(4e6, rel=0.01)


# --- chapter 13: the search ---------------------------------------------------------------


def test_gates_and_hypothesis_counts_quoted_in_the_chapter() -> None:
    text = chapter("13-jcbb.md")
    assert "(5.99, 9.49, 12.59)" in text
    assert [round(float(chi2.ppf(0.95, 2 * k)), 2) for k in (1, 2, 3)] == [5.99, 9.49, 12.59]

    # Σ_k C(m, k) N!/(N − k)!: choose which measurements pair, then distinct landmarks in order
    def count(m: int, n: int) -> int:
        return sum(math.comb(m, k) * math.perm(n, k) for k in range(min(m, n) + 1))

    assert count(2, 2) == 7 and count(4, 4) == 209
    assert "has 7 of them" in text and "already have 209" in text
    assert jcbb.jcbb_hypotheses([0] * 7, None, [[1, 0]] * 2, None, 0.95) == 7
    assert jcbb.jcbb_hypotheses([0] * 11, None, [[1, 0]] * 4, None, 0.95) == 209


def test_scene_jcbb_against_greedy() -> None:
    from slamcourse.slam import jcbb as lib

    z = jcbb.scene_measurements()
    args = (list(jcbb.SCENE_MU), jcbb.SCENE_P, z, jcbb.SCENE_R, 0.95)
    assert jcbb.jcbb_search(*args) == [0, 1]
    assert lib.greedy_nn(*args) == (0, 0)


@FAST
@given(jcbb.jcbb_inputs())
def test_jcbb_search_equals_a_brute_force_written_here(kw: dict[str, Any]) -> None:
    if not jcbb.jcbb_valid(**kw):
        return
    mu, p, z, r, conf = (kw[k] for k in ("mu", "P", "z", "R", "confidence"))
    from slamcourse.slam import ekfslam

    m = np.asarray(mu)
    landmarks = (m.size - 3) // 2

    def d2(pairs: list[tuple[int, int]]) -> float:
        nus, hs = [], []
        for i, j in pairs:
            pred = ekfslam.observe(m[:3], m[3 + 2 * j : 5 + 2 * j])
            nu = np.asarray(z[i]) - pred
            nus.append([nu[0], math.remainder(nu[1], 2 * math.pi)])
            hs.append(ekfslam.observation_jacobian(m, j))
        h = np.vstack(hs)
        s = h @ np.asarray(p) @ h.T + np.kron(np.eye(len(pairs)), r)
        v = np.concatenate(nus)
        return float(v @ np.linalg.inv(s) @ v)

    best: tuple[int, float, tuple[int, ...]] = (0, 0.0, tuple([-1] * len(z)))
    for hyp in itertools.product(range(-1, landmarks), repeat=len(z)):
        pairs = [(i, j) for i, j in enumerate(hyp) if j >= 0]
        if not pairs or len({j for _, j in pairs}) < len(pairs):
            continue
        if any(d2([pair]) >= chi2.ppf(conf, 2) for pair in pairs):
            continue
        value = d2(pairs)
        if value >= chi2.ppf(conf, 2 * len(pairs)):
            continue
        if len(pairs) > best[0] or (len(pairs) == best[0] and value < best[1]):
            best = (len(pairs), value, hyp)
    assert tuple(jcbb.jcbb_search(**kw)) == best[2]


# --- pictures and figures -----------------------------------------------------------------


@pytest.mark.parametrize(
    "key",
    ["vision/four-candidates", "occupancy/prior-readings"],
)
def test_prose_figures_are_accessible_svg_placed_in_their_chapter(key: str) -> None:
    from slamcourse.plots.registry import FIGURES

    root = ET.fromstring(FIGURES[key]())
    ns = "{http://www.w3.org/2000/svg}"
    title = root.find(f"{ns}title")
    desc = root.find(f"{ns}desc")
    assert title is not None and title.text
    assert desc is not None and desc.text and len(desc.text) > 40
    name = {"vision": "06-vision.md", "occupancy": "08-occupancy.md"}[key.split("/")[0]]
    assert f"```{{figure}} {key}\n" in chapter(name)


def test_figure_descriptions_state_the_quoted_figures() -> None:
    from slamcourse.plots import ch_gaps

    four = ch_gaps.four_candidates()
    for pair in ("(1, 1)", "(−1, −1)", "(1, −1)", "(−1, 1)"):
        assert pair in four or pair.replace("−", "-") in four
    assert "2.4e-07" in ch_gaps.prior_readings()


@pytest.mark.parametrize(
    "exercise", ["vision/decompose-essential", "ekf-slam/slam-step", "jcbb/jcbb-search"]
)
def test_code_exercise_pictures_draw_the_givens(exercise: str) -> None:
    from slamcourse.plots.registry import BY_ID

    picture = BY_ID[exercise]
    assert not picture.after_solving
    svg = picture.draw({}, False)
    assert ET.fromstring(svg).tag.endswith("svg")


# --- the new number exercises' canonical answers, by hand -------------------------------------


def test_canonical_answers_of_the_new_number_exercises() -> None:
    from slamcourse.course.loader import load_course
    from slamcourse.course.variants import variant
    from slamcourse.kinds import get_kind

    course = load_course(ROOT)

    def canonical(eid: str) -> Any:
        spec = course.exercise(eid)
        return get_kind(spec.kind).expected(spec, variant(spec, 0))

    # the edge x_1 → x_3, d = 2.5, ω = 4
    omega = [[0, 0, 0, 0], [0, 4, 0, -4], [0, 0, 0, 0], [0, -4, 0, 4]]
    assert np.array_equal(np.asarray(canonical("graph/edge-omega"), dtype=float), omega)
    assert np.allclose(canonical("graph/edge-xi"), [0, -10, 0, 10])
    # centroid (375, 205); distances √133250, √63850, √80450, √7650
    mean = (math.sqrt(133250) + math.sqrt(63850) + math.sqrt(80450) + math.sqrt(7650)) / 4
    s = math.sqrt(2) / mean
    want = [[s, 0, -375 * s], [0, s, -205 * s], [0, 0, 1]]
    assert np.allclose(canonical("vision/hartley-normalise"), want, rtol=1e-12, atol=1e-15)
    # odds: prior 1/4, readings 9 and 3/7, each over the prior's odds: (1/4)·36·(12/7) = 108/7
    assert np.allclose(canonical("occupancy/prior-update"), [math.log(108 / 7), 108 / 115])
