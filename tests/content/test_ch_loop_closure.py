"""Content tests of chapter ``loop-closure``.

1. every figure quoted in the chapter's prose and exercise texts, recomputed independently of
   the reference module's route (another formula, a brute force, a printed table);
2. the prose figures and exercise pictures are accessible SVG;
3. every code exercise ships ≥ 8 mutants and ≥ 3 variants, each saying what it is (that each
   mutant fails and each variant passes in the real sandbox is checked once, by
   ``test_bundled_course.py::test_exercise_is_sound``).
"""

from __future__ import annotations

import importlib.util
import math
import xml.etree.ElementTree as ET
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from slamcourse.plots import ch_loop_closure as plots
from slamcourse.slam import loopclosure as lc
from slamcourse.slam import posegraph as pg
from slamcourse.slam import se2

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = "loop-closure"
FOLDER = ROOT / "exercises" / CHAPTER


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("_ref_loop_closure", FOLDER / "reference.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ref = _load()


def _joint_of(cov: np.ndarray, i: int, j: int) -> np.ndarray:
    idx = [*range(3 * i, 3 * i + 3), *range(3 * j, 3 * j + 3)]
    return np.asarray(cov[np.ix_(idx, idx)])


def _nis_by_hand(
    x: np.ndarray, cov: np.ndarray, i: int, j: int, z: tuple[float, ...], om: np.ndarray
) -> float:
    """The NIS through pose i's frame: ν = (x_i⁻¹ ⊕ x_j) − z, S = Σ_r + R_z Ω⁻¹ R_zᵀ, with the
    relative covariance from a finite-difference Jacobian (not the module's formulas)."""
    xi, xj = x[i], x[j]
    h = 1e-6
    base = np.array([*xi, *xj])
    jac = np.zeros((3, 6))
    for k in range(6):
        up, down = base.copy(), base.copy()
        up[k] += h
        down[k] -= h
        d = np.array(se2.between(up[:3], up[3:])) - np.array(se2.between(down[:3], down[3:]))
        d[2] = se2.wrap_angle(d[2])
        jac[:, k] = d / (2 * h)
    r = np.array(se2.between(xi, xj))
    nu = np.array([r[0] - z[0], r[1] - z[1], se2.wrap_angle(r[2] - z[2])])
    rz = np.eye(3)
    rz[:2, :2] = se2.rotation(z[2])
    s = jac @ _joint_of(cov, i, j) @ jac.T + rz @ np.linalg.inv(om) @ rz.T
    return float(nu @ np.linalg.solve(s, nu))


def _dense_cov(x: np.ndarray, edges: list[pg.Edge]) -> np.ndarray:
    """``H⁻¹`` with pose 0 fixed, from an ``H`` assembled edge by edge here."""
    n = len(x)
    h = np.zeros((3 * n, 3 * n))
    for e in edges:
        a, b = pg.edge_jacobians(x[e.i], x[e.j], e.z)
        for p, jp in ((e.i, a), (e.j, b)):
            for q, jq in ((e.i, a), (e.j, b)):
                h[3 * p : 3 * p + 3, 3 * q : 3 * q + 3] += jp.T @ e.information @ jq
    cov = np.zeros_like(h)
    cov[3:, 3:] = np.linalg.inv(h[3:, 3:])
    return cov


# --- 1. the figures of the prose --------------------------------------------------------------


def test_intel_closure_geometry() -> None:
    closures = [e for e in ref.intel().edges if abs(e.i - e.j) != 1]
    assert len(closures) == 256
    assert sum(1 for e in closures if abs(e.z[2]) > math.pi / 2) == 97
    assert max(math.hypot(e.z[0], e.z[1]) for e in closures) == pytest.approx(2.99, abs=0.005)


def test_odometry_uncertainty_figures() -> None:
    """σ at poses 15 and 166 from H⁻¹ of the chain (not the recursion the figure uses)."""
    x, _ = plots.odometry_chain()
    chain = [e for e in ref.intel().edges if e.j == e.i + 1 and e.j <= 166]
    cov = _dense_cov(x, chain)

    def largest_sd(k: int) -> float:
        return math.sqrt(float(np.linalg.eigvalsh(cov[3 * k : 3 * k + 2, 3 * k : 3 * k + 2])[-1]))

    assert largest_sd(15) == pytest.approx(0.94, abs=0.005)
    assert largest_sd(166) == pytest.approx(4.5, abs=0.05)
    assert math.sqrt(cov[3 * 15 + 2, 3 * 15 + 2]) == pytest.approx(0.11, abs=0.005)
    assert math.sqrt(cov[3 * 166 + 2, 3 * 166 + 2]) == pytest.approx(0.31, abs=0.005)


def test_first_return_candidates_by_brute_force() -> None:
    """Poses 14–34 (21 of them, pose 19 among them) pass the 95 % χ²₂ gate for pose 166."""
    snap = ref.arrival(166)
    assert snap.first == 14
    cov = _dense_cov(snap.poses, list(snap.edges))
    k = len(snap.poses) - 1
    chosen = []
    for i in range(k - 20 + 1):
        xi, xk = snap.poses[i], snap.poses[k]
        c, s = math.cos(xi[2]), math.sin(xi[2])
        d = xk[:2] - xi[:2]
        t = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])
        jac = np.array(
            [[-c, -s, t[1], c, s, 0.0], [s, -c, -t[0], -s, c, 0.0]]
        )  # ∂(R_iᵀ (t_k − t_i))/∂(x_i, x_k)
        sigma = jac @ _joint_of(cov, i, k) @ jac.T
        if float(t @ np.linalg.solve(sigma, t)) <= 5.991464547107979:
            chosen.append(i + snap.first)
    assert chosen == list(range(14, 35))
    assert plots.gate_candidates()[1] == chosen


def test_first_return_search_mistakes_by_brute_force() -> None:
    """The prose's costs of each mistake for pose 166 (95 %, gap 20): without Σ_ik 43 poses
    (14–36 and 127–146), Euclidean 6 (14–19), the whole pose against χ²₃ 17 (14–30); computed
    here from an H⁻¹ assembled in this file and finite-difference Jacobians."""
    snap = ref.arrival(166)
    cov = _dense_cov(snap.poses, list(snap.edges))
    x = snap.poses
    k = len(x) - 1
    h = 1e-6

    def jacobian(i: int) -> np.ndarray:
        base = np.array([*x[i], *x[k]])
        jac = np.zeros((3, 6))
        for a in range(6):
            up, down = base.copy(), base.copy()
            up[a] += h
            down[a] -= h
            d = np.array(se2.between(up[:3], up[3:])) - np.array(se2.between(down[:3], down[3:]))
            d[2] = se2.wrap_angle(d[2])
            jac[:, a] = d / (2 * h)
        return jac

    gate2 = -2 * math.log(1 - 0.95)
    gate3 = 7.814727903251179  # χ²₃ at 95 %, from printed tables
    right, no_cross, euclid, whole = [], [], [], []
    for i in range(k - 20 + 1):
        jac = jacobian(i)
        joint = _joint_of(cov, i, k)
        independent = joint.copy()
        independent[:3, 3:] = independent[3:, :3] = 0.0
        r = np.array(se2.between(x[i], x[k]))
        r[2] = se2.wrap_angle(r[2])
        t = r[:2]
        pose = i + snap.first
        if t @ np.linalg.solve((jac @ joint @ jac.T)[:2, :2], t) <= gate2:
            right.append(pose)
        if t @ np.linalg.solve((jac @ independent @ jac.T)[:2, :2], t) <= gate2:
            no_cross.append(pose)
        if t @ t <= gate2:
            euclid.append(pose)
        if r @ np.linalg.solve(jac @ joint @ jac.T, r) <= gate3:
            whole.append(pose)
    assert right == list(range(14, 35))
    assert no_cross == [*range(14, 37), *range(127, 147)] and len(no_cross) == 43
    assert euclid == list(range(14, 20))
    assert whole == list(range(14, 31)) and len(whole) == 17
    # the reference's misconceptions say the same on the figure's search
    m = [lc.block(snap.cov, i, i) for i in range(k + 1)]
    c = [lc.block(snap.cov, i, k) for i in range(k + 1)]
    kw = {"poses": x, "marginals": m, "cross": c, "gap": 20, "confidence": 0.95}
    assert [i + snap.first for i in ref.loop_candidates(**kw)] == right
    assert [i + snap.first for i in ref.mistake_cand_no_cross(**kw)] == no_cross
    assert [i + snap.first for i in ref.mistake_cand_euclidean(**kw)] == euclid
    assert [i + snap.first for i in ref.mistake_cand_full_pose(**kw)] == whole


def test_candidate_search_inputs_are_intel_arrivals() -> None:
    """The exercise's INTEL inputs: the last 200 poses (at most) of the graph held on each
    arrival, ending at the arrival pose; the blocks those of that graph's H⁻¹; and for pose
    166 the candidates of a brute force at the input's own gap and confidence."""
    searches = ref.intel_searches()
    assert len(searches) == len(ref.ARRIVALS) == 8
    for j, search in zip(ref.ARRIVALS, searches, strict=True):
        snap = ref.arrival(j)
        n = len(search["poses"])
        assert n == min(len(snap.poses), 200)
        assert np.allclose(search["poses"][-1], snap.poses[-1], atol=1e-9)
        assert np.allclose(search["cross"][-1], search["marginals"][-1])
        assert ref.search_valid(**search)
    first = searches[0]
    snap = ref.arrival(166)
    cov = _dense_cov(snap.poses, list(snap.edges))
    x = snap.poses
    k = len(x) - 1
    gap, confidence = first["gap"], first["confidence"]
    chosen = []
    for i in range(k - gap + 1):
        c, s = math.cos(x[i][2]), math.sin(x[i][2])
        d = x[k][:2] - x[i][:2]
        t = np.array([c * d[0] + s * d[1], -s * d[0] + c * d[1]])
        jac = np.array([[-c, -s, t[1], c, s, 0.0], [s, -c, -t[0], -s, c, 0.0]])
        if float(t @ np.linalg.solve(jac @ _joint_of(cov, i, k) @ jac.T, t)) <= -2 * math.log(
            1 - confidence
        ):
            chosen.append(i)
    assert ref.loop_candidates(**first) == chosen


def test_nis_of_closures_on_arrival() -> None:
    """16 true closures between 0.04 and 4.4; moved 25 poses: 18 to 732, all rejected; moved 8
    poses: 4.1 to 1031, one accepted (27 → 166 at 4.1, against the true 19 → 166 at 0.4)."""
    true, off8, off25 = [], [], []
    for j in ref.ARRIVALS:
        snap = ref.arrival(j)
        cov = _dense_cov(snap.poses, list(snap.edges))
        for e in ref.closures_at(j):
            a, b = snap.local(e.i), snap.local(j)
            true.append(_nis_by_hand(snap.poses, cov, a, b, e.z, e.information))
            for shift, out in ((8, off8), (25, off25)):
                if a + shift < b - 5:
                    out.append(_nis_by_hand(snap.poses, cov, a + shift, b, e.z, e.information))
    gate = 7.814727903251179
    assert len(ref.ARRIVALS) == 8 and len(true) == 16
    assert min(true) == pytest.approx(0.04, abs=0.005) and max(true) == pytest.approx(4.4, abs=0.05)
    assert min(off25) == pytest.approx(18, abs=0.5) and max(off25) == pytest.approx(732, abs=0.5)
    assert min(off25) > gate
    assert min(off8) == pytest.approx(4.1, abs=0.05) and max(off8) == pytest.approx(1031, abs=0.5)
    assert sum(1 for v in off8 if v <= gate) == 1
    assert true[0] == pytest.approx(0.4, abs=0.05) and off8[0] == pytest.approx(4.1, abs=0.05)
    # and the exercise's inputs are these very closures (INTEL's H is ill-conditioned, its
    # information spans 11 to 2.7e12: two assemblies of H⁻¹ agree to about 1e-3)
    assert [ref.closure_nis(**d) for d in ref.intel_closures()][:2] == pytest.approx(
        [true[0], off8[0]], rel=2e-3
    )
    # on the first return, pose 166 is uncertain by metres relative to pose 19
    snap = ref.arrival(166)
    p = ref.relative_pose_covariance(**ref._blocks(snap, 19, 166))
    assert np.sqrt(np.diag(p))[:2] == pytest.approx([4.16, 3.64], abs=0.01)


def _chi2_by_edge(x: np.ndarray, edges: list[pg.Edge]) -> float:
    total = 0.0
    for e in edges:
        r = se2.between(x[e.i], x[e.j])
        err = np.array(se2.compose(se2.inverse(e.z), r))
        err[2] = se2.wrap_angle(err[2])
        total += float(err @ e.information @ err)
    return total


def test_false_closure_figures() -> None:
    graph = ref.intel()
    edges = [*graph.edges, ref.false_closure_edge()]
    assert len(edges) == 1484
    x, _ = ref.false_closure_run()
    # converged, and the χ² re-evaluated edge by edge with the SE(2) functions
    again = pg.gauss_newton_step(x, edges)
    assert np.max(np.abs(pg.relative_to_first(again) - pg.relative_to_first(x))) < 1e-5
    assert _chi2_by_edge(x, edges) == pytest.approx(1614.55, abs=0.005)
    assert ref.false_closure_chi2() == pytest.approx(1614.55, abs=0.005)
    assert _chi2_by_edge(ref.intel_optimum()[0], list(graph.edges)) == pytest.approx(
        215.83, abs=0.005
    )
    assert 7 < 1614.55 / 215.83 < 8  # "more than sevenfold"
    assert ref.false_closure_edge_chi2() == pytest.approx(400, rel=0.02)
    assert ref.false_closure_shift() == pytest.approx(4.1, abs=0.05)
    good = ref.intel_optimum()[0]
    assert math.hypot(*se2.between(good[50], good[223])[:2]) == pytest.approx(10, abs=0.5)
    # the NIS before adding it: about 1530, some 200 times the gate; the two poses' joint
    # covariance here from a dense Cholesky of H (the module uses a sparse LU)
    import scipy.linalg

    f = ref.false_closure_edge()
    h, _ = pg.linear_system(good, list(graph.edges))
    factor = scipy.linalg.cho_factor(h[3:, 3:])
    cov = np.zeros_like(h)
    cols = [*range(3 * f.i, 3 * f.i + 3), *range(3 * f.j, 3 * f.j + 3)]
    unit = np.zeros((len(h) - 3, 6))
    for c, col in enumerate(cols):
        unit[col - 3, c] = 1.0
    solved = scipy.linalg.cho_solve(factor, unit)
    for c, col in enumerate(cols):
        cov[3:, col] = solved[:, c]
    nis = _nis_by_hand(good, cov, f.i, f.j, f.z, f.information)
    assert nis == pytest.approx(1530, rel=0.005)
    assert ref.false_closure_nis() == pytest.approx(nis, rel=1e-5)
    assert 190 < nis / 7.8147 < 210


def test_numeric_exercises_by_hand() -> None:
    assert ref.gate(confidence=0.95) == pytest.approx(7.815, abs=1e-3)
    assert ref.gate(confidence=0.99) == pytest.approx(11.345, abs=1e-3)
    # 1.2² + 1.5² − 2·0.95·1.2·1.5
    assert ref.difference_variance(si=1.2, sj=1.5, rho=0.95) == pytest.approx(0.27)
    # canonical Mahalanobis: t = (2.4, −1.1), Σ = [[1.8, s], [s, 0.6]], s = 0.5·√(1.8·0.6)
    s = 0.5 * math.sqrt(1.08)
    det = 1.8 * 0.6 - s * s
    d2 = (0.6 * 2.4**2 - 2 * s * 2.4 * -1.1 + 1.8 * 1.1**2) / det
    assert ref.mahalanobis_value(tx=2.4, ty=-1.1, sxx=1.8, syy=0.6, sxy=s, c=0.5) == pytest.approx(
        d2
    )


# --- 2. figures and pictures ------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(plots.FIGURES))
def test_figures_are_accessible_svg(name: str) -> None:
    svg = plots.FIGURES[name]()
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    assert root.find(f"{ns}title") is not None and root.find(f"{ns}desc") is not None
    assert (root.find(f"{ns}desc").text or "").strip()  # type: ignore[union-attr]


def test_figure_descriptions_quote_the_tested_numbers() -> None:
    assert "21 poses, 14 to 34" in plots.candidate_gate()
    assert "4.48 m at pose 166" in plots.odometry_uncertainty()
    assert "up to 4.13 m" in plots.false_closure()


@pytest.mark.parametrize("exercise", sorted(plots.PICTURES))
def test_pictures_draw_givens(exercise: str) -> None:
    picture = plots.PICTURES[exercise]
    assert not picture.after_solving
    root = ET.fromstring(picture.draw({}, False))
    assert root.find("{http://www.w3.org/2000/svg}desc") is not None


def test_every_prose_figure_is_placed_in_the_chapter() -> None:
    text = (ROOT / "chapters" / "20-loop-closure.md").read_text(encoding="utf-8")
    for name in plots.FIGURES:
        assert f"```{{figure}} {name}" in text


# --- 3. enough mutants and variants -----------------------------------------------------------


def test_enough_mutants_and_variants() -> None:
    for yaml_path in sorted(FOLDER.glob("*.yaml")):
        if "kind: code" not in yaml_path.read_text(encoding="utf-8"):
            continue
        mutants = sorted((FOLDER / "mutants" / yaml_path.stem).glob("*.py"))
        variants = sorted((FOLDER / "variants" / yaml_path.stem).glob("*.py"))
        assert len(mutants) >= 8 and len(variants) >= 3, yaml_path.stem
        assert all(p.read_text(encoding="utf-8").startswith("# mistake: ") for p in mutants)
        assert all(p.read_text(encoding="utf-8").startswith("# method: ") for p in variants)
