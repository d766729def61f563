"""Content tests of chapter ``marginalisation``.

1. every figure the prose quotes, pinned against an independent computation (the INTEL file
   read line by line, forward covariance propagation along the chain, hand formulas, numeric
   Schur complements), and found in the chapter's text as written;
2. the canonical answers of the numeric exercises, by hand;
3. the prose figures and pictures draw accessible SVG stating those figures;
4. every code exercise has enough mutants and correct variants (graded, once, by
   ``test_bundled_course.py``).
"""

from __future__ import annotations

import importlib.util
import itertools
import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from slamcourse.plots import ch_marginalisation as plots

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = "marginalisation"
PROSE = (ROOT / "chapters" / "21-marginalisation.md").read_text(encoding="utf-8")
INTEL = ROOT / "exercises" / "intel" / "data" / "input_INTEL.g2o"


def load_reference() -> ModuleType:
    path = ROOT / "exercises" / CHAPTER / "reference.py"
    spec = importlib.util.spec_from_file_location("_ref_marginalisation", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ref = load_reference()


def in_prose(phrase: str) -> None:
    flat = " ".join(PROSE.split())
    assert phrase in flat, f"the chapter no longer says {phrase!r}"


# --- INTEL, read independently of slamcourse.slam -------------------------------------------------


def intel_lines() -> tuple[dict[int, tuple[float, ...]], list[tuple[int, int, list[float]]]]:
    vertices, edges = {}, []
    for line in INTEL.read_text(encoding="utf-8").splitlines():
        f = line.split()
        if f and f[0] == "VERTEX_SE2":
            vertices[int(f[1])] = tuple(float(v) for v in f[2:5])
        elif f and f[0] == "EDGE_SE2":
            edges.append((int(f[1]), int(f[2]), [float(v) for v in f[3:12]]))
    return vertices, edges


def chain_by_propagation(last: int) -> tuple[np.ndarray, np.ndarray]:
    """Marginal and conditional covariances of pose ``last`` (pose 0 fixed) by compounding the
    odometry forward: ``x_j = (x_i ⊕ z) ⊕ ε`` with ``ε ~ N(0, Ω⁻¹)``, the noise model whose
    linearisation is the pose graph's ``H``."""
    vertices, edges = intel_lines()
    odometry = {i: v for i, j, v in edges if j == i + 1}
    sigma = np.zeros((3, 3))
    cond = np.zeros((3, 3))
    for i in range(last):
        v = odometry[i]
        dx, dy, dt = v[:3]
        i11, i12, i13, i22, i23, i33 = v[3:]
        assert i13 == 0 and i23 == 0  # heading decoupled from position
        om = np.array([[i11, i12, 0], [i12, i22, 0], [0, 0, i33]])
        th = vertices[i][2]
        c, s = math.cos(th), math.sin(th)
        j_pose = np.array([[1, 0, -s * dx - c * dy], [0, 1, c * dx - s * dy], [0, 0, 1]])
        tj = th + dt
        j_noise = np.array(
            [[math.cos(tj), -math.sin(tj), 0], [math.sin(tj), math.cos(tj), 0], [0, 0, 1]]
        )
        cond = j_noise @ np.linalg.inv(om) @ j_noise.T
        sigma = j_pose @ sigma @ j_pose.T + cond
    return sigma, cond


def test_intel_chain_ends_before_the_first_loop_closure() -> None:
    _, edges = intel_lines()
    first = min(max(i, j) for i, j, _ in edges if abs(i - j) != 1)
    assert first == 166 == ref.first_loop_closure()
    in_prose("the first loop closure arrives at pose 166")


def test_intel_marginal_and_conditional_sigmas_quoted_in_the_prose() -> None:
    sigma, cond = chain_by_propagation(100)
    marginal = np.sqrt(np.diag(sigma))
    conditional = np.sqrt(np.diag(cond))
    assert ref.intel_marginal_sigmas(100) == pytest.approx(marginal, rel=1e-4)
    assert ref.intel_conditional_sigmas(100) == pytest.approx(conditional, rel=1e-4)
    assert f"{marginal[2]:.3f}" == "0.234"
    assert round(math.degrees(marginal[2])) == 13
    assert (f"{marginal[0]:.2f}", f"{marginal[1]:.2f}") == ("3.89", "3.13")
    assert (f"{conditional[2]:.3f}", f"{conditional[0]:.2f}", f"{conditional[1]:.3f}") == (
        "0.021",
        "0.30",
        "0.068",
    )
    in_prose("deviation of pose 100's heading is 0.234 rad, about 13°")
    in_prose("3.89 m in $x$ and 3.13 m in $y$")
    in_prose("are 0.021 rad, 0.30 m and 0.068 m")
    # "eleven times" (heading) and "up to forty-six times" (position)
    assert round(marginal[2] / conditional[2]) == 11
    assert round(max(marginal[:2] / conditional[:2])) == 46
    in_prose("pose 100's heading look eleven times, and its position up to forty-six times")


def test_intel_heading_sigma_is_a_sum_of_edge_variances() -> None:
    """With the heading decoupled, the variances of the chain's headings add up."""
    _, edges = intel_lines()
    odometry = {i: v for i, j, v in edges if j == i + 1}
    assert all(odometry[i][5] == 0 and odometry[i][7] == 0 for i in range(150))
    for last in (20, 50, 100, 150):
        by_sum = math.sqrt(sum(1 / odometry[i][8] for i in range(last)))
        assert ref.intel_heading_sigma(last) == pytest.approx(by_sum, rel=1e-6)
    assert f"{ref.intel_heading_sigma(150):.3f}" == "0.283"
    assert f"{1 / math.sqrt(odometry[0][8]):.2f}" == "0.02"
    in_prose("it grows from 0.02 rad to 0.283 rad at pose 150")


def test_intel_inverse_size() -> None:
    assert 3 * (1228 - 1) == 3681
    assert f"{3681**2 / 1e6:.1f}" == "13.5"
    in_prose("a dense $3681 \\times 3681$ matrix, 13.5 million numbers")


# --- the rail, the window -------------------------------------------------------------------------


def test_scalar_and_rail_figures() -> None:
    # H = [[29, -25], [-25, 25]]: Σ = H⁻¹ by the 2×2 formula
    det = 29 * 25 - 25 * 25
    assert det == 100
    assert 29 / det == pytest.approx(0.25 + 0.04)
    assert f"{math.sqrt(29 / det):.3f}" == "0.539"
    assert 1 / math.sqrt(25) == 0.2
    in_prose("($\\sigma = 0.539$ m)")
    in_prose("at a known $x_0$ ($\\sigma = 0.2$ m)")
    in_prose("$(H^{-1})_{11} = 29/100 = 0.29$ m²")
    # springs in series: 25·16/41, the variances 1/25 + 1/16
    assert f"{25 * 16 / 41:.2f}" == "9.76"
    assert math.isclose(1 / 25 + 1 / 16, 0.04 + 0.0625)
    assert np.allclose(
        ref.chain_schur(p=4, w1=25, w2=16),
        [[29 - 625 / 41, -400 / 41], [-400 / 41, 16 - 256 / 41]],
        rtol=1e-12,
    )
    in_prose("has become $-400/41 \\approx -9.76$")


def numeric_fill(n: int, edges: list[tuple[int, int]], removed: list[int]) -> set[tuple[int, int]]:
    """New nonzero pairs of a real Schur complement of a random SPD matrix with this pattern."""
    rng = np.random.default_rng(3)
    h = np.zeros((n, n))
    for i, j in edges:
        h[i, j] = h[j, i] = rng.uniform(0.1, 1.0)
    h += np.diag(h.sum(axis=1) + 1.0)
    keep = [i for i in range(n) if i not in removed]
    m = removed
    h_new = h[np.ix_(keep, keep)] - h[np.ix_(keep, m)] @ np.linalg.solve(
        h[np.ix_(m, m)], h[np.ix_(m, keep)]
    )
    linked = {tuple(sorted(e)) for e in edges}
    return {
        (keep[r], keep[c])
        for r, c in itertools.combinations(range(len(keep)), 2)
        if abs(h_new[r, c]) > 1e-12 and (keep[r], keep[c]) not in linked
    }


def test_window_figure_counts() -> None:
    names, edges = plots.window_graph(4, plots.WINDOW_SIGHTINGS)
    fill = numeric_fill(len(names), edges, [0])
    assert len(fill) == 8
    blanket = {v for e in edges for v in e if 0 in e} - {0}
    assert sorted(names[v] for v in blanket) == ["l0", "l1", "l2", "l3", "x1"]
    in_prose("leaves a dense prior on its five neighbours: 8 new pairs")
    in_prose("$x_0$ saw $l_0$, $l_1$, $l_2$ and $l_3$, $x_1$ saw $l_0$ and $l_3$")


# --- canonical answers ----------------------------------------------------------------------------


def test_canonical_answers() -> None:
    assert ref.scalar_marginal(a=29, c=-25, d=41) == pytest.approx(41 / (29 * 41 - 625))
    assert ref.mistake_scalar_conditional(a=29, c=-25, d=41) == pytest.approx(1 / 29)
    assert ref.prior_size(seen=5, shared=2) == 3 + 2 * 5
    assert ref.fill_count(seen=6, shared=2) == math.comb(7, 2) - 2
    for seen, shared in ((2, 1), (6, 2), (12, 11)):
        names, edges = plots.window_graph(2, [tuple(range(seen)), tuple(range(shared))])
        assert ref.fill_count(seen=seen, shared=shared) == len(numeric_fill(len(names), edges, [0]))
    assert ref.ba_reduced_size(cameras=10, points=200) == 60
    assert ref.mistake_ba_full(cameras=10, points=200) == 660


# --- figures and pictures -------------------------------------------------------------------------


def parsed(svg: str) -> tuple[str, str]:
    root = ET.fromstring(svg)
    ns = "{http://www.w3.org/2000/svg}"
    title, desc = root.find(f"{ns}title"), root.find(f"{ns}desc")
    assert title is not None and desc is not None and title.text and desc.text
    return title.text, desc.text


def test_prose_figures_are_placed_and_draw() -> None:
    placed = set(re.findall(r"```\{figure\} (\S+)", PROSE))
    assert placed == set(plots.FIGURES)
    descs = {key: parsed(draw())[1] for key, draw in plots.FIGURES.items()}
    assert "is 0.539 m" in descs["marginalisation/marginal-vs-conditional"]
    assert "x0 = 0, is 0.2 m" in descs["marginalisation/marginal-vs-conditional"]
    assert "to 0.283 rad at pose 150" in descs["marginalisation/intel-chain-sigma"]
    assert "0.02 rad at pose 1 " in descs["marginalisation/intel-chain-sigma"]
    assert "between 0.014 and 0.0234 rad" in descs["marginalisation/intel-chain-sigma"]
    in_prose("which stays between 0.014 and 0.023 rad")
    assert "5 neighbours (x1, l0, l1, l2, l3): 8 pairs" in descs["marginalisation/window-fill"]


def test_pictures_draw_and_hide_counts() -> None:
    for key in ("marginalisation/fill-count", "marginalisation/prior-size"):
        picture = plots.PICTURES[key]
        assert picture.after_solving
        _, desc = parsed(picture.draw({"seen": 6, "shared": 2}, True))
        assert f"{ref.fill_count(seen=6, shared=2)} pairs" in desc
    for key in ("marginalisation/marginalise", "marginalisation/marginal-covariance"):
        parsed(plots.PICTURES[key].draw({}, False))


# --- mutants and variants ------------------------------------------------------------------------
# Each is graded through the real sandbox once, by the course's validation
# (test_bundled_course.py::test_exercise_is_sound: mutants fail, variants pass); here, only that
# there are enough of them.


def test_code_exercises_have_enough_mutants_and_variants() -> None:
    folder = ROOT / "exercises" / CHAPTER
    for slug in ("marginalise", "marginal-covariance"):
        mutants = sorted((folder / "mutants" / slug).glob("*.py"))
        variants = sorted((folder / "variants" / slug).glob("*.py"))
        assert len(mutants) >= 8 and len(variants) >= 3
        assert all(p.read_text(encoding="utf-8").startswith("# mistake: ") for p in mutants)
        assert all(p.read_text(encoding="utf-8").startswith("# method: ") for p in variants)
