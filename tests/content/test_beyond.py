"""Content tests for the chapters beyond the lesson (``se2`` onwards).

1. canonical answers pinned by hand, independently of the reference code;
2. every code exercise ships ≥ 8 mutants (``exercises/<chapter>/mutants/<slug>/NN-name.py``,
   first line ``# mistake: …``) and ≥ 3 variants (``variants/<slug>/NN-name.py``, first line
   ``# method: …``). That each mutant fails and each variant passes in the real sandbox is
   checked once, by ``test_bundled_course.py::test_exercise_is_sound``.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.kinds import get_kind

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = ("se2", "motion", "pose-graph", "intel")
COURSE = load_course(bundled_course_root())


def load_reference(chapter: str) -> ModuleType:
    path = ROOT / "exercises" / chapter / "reference.py"
    spec = importlib.util.spec_from_file_location(f"_ref_beyond_{chapter.replace('-', '_')}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


se2 = load_reference("se2")
motion = load_reference("motion")
pose_graph = load_reference("pose-graph")
intel = load_reference("intel")


# --- 1. canonical answers ---------------------------------------------------------------------


def test_se2_canonical_answers() -> None:
    assert se2.wrapped(a=5.5) == pytest.approx(5.5 - 2 * math.pi)
    assert se2.mistake_wrap_zero_to_two_pi(a=5.5) == pytest.approx(5.5)
    # (1, 0, π/2) ⊕ (1, 0, π/4): one metre along the robot's x, which points along the world's y
    assert se2.composed(xa=1, ya=0, ta=math.pi / 2, xb=1, yb=0, tb=math.pi / 4) == pytest.approx(
        [1, 1, 3 * math.pi / 4]
    )
    assert se2.inverted(x=2, y=1, t=math.pi / 2) == pytest.approx([-1, 2, -math.pi / 2])
    assert se2.relative(xa=1, ya=1, ta=math.pi / 2, xb=1, yb=3, tb=math.pi) == pytest.approx(
        [2, 0, math.pi / 2]
    )
    assert se2.wrap_angle(-math.pi) == math.pi


def test_motion_canonical_answers() -> None:
    # turn 0.3 from π/4, drive 1.5 m along π/4 + 0.3, turn −0.2
    h = math.pi / 4 + 0.3
    assert motion.step_value(x=2, y=1, t=math.pi / 4, rot1=0.3, trans=1.5, rot2=-0.2) == (
        pytest.approx([2 + 1.5 * math.cos(h), 1 + 1.5 * math.sin(h), h - 0.2])
    )
    # Σ'_yy = 0.01 + 2²·0.004 + 2²·0.003
    assert motion.lateral_variance(trans=2, var_y=0.01, var_t=0.004, var_rot1=0.003) == (
        pytest.approx(0.038)
    )
    # straight along +x: forward variance grows only by M_trans, heading by M_rot1 + M_rot2
    cov = motion.predict_covariance(
        pose=[0, 0, 0],
        u=[0, 2, 0],
        sigma=[[0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.004]],
        motion_cov=[[0.003, 0, 0], [0, 0.02, 0], [0, 0, 0.001]],
    )
    assert cov[0][0] == pytest.approx(0.03)
    assert cov[2][2] == pytest.approx(0.008)
    assert cov[1][2] == pytest.approx(2 * 0.004 + 2 * 0.003)


def test_pose_graph_canonical_answers() -> None:
    # x_i = (0, 0, 0.5), x_j = (1.1, 0.9, 1.6), z = (1, 1, π/2): rotate the offset by −0.5, subtract
    # z's translation, rotate by −π/2 (which maps (u, v) to (v, −u))
    c, s = math.cos(0.5), math.sin(0.5)
    u, v = c * 1.1 + s * 0.9 - 1, -s * 1.1 + c * 0.9 - 1
    e = pose_graph.error_value(
        xi=0, yi=0, ti=0.5, xj=1.1, yj=0.9, tj=1.6, zx=1, zy=1, zt=math.pi / 2
    )
    assert e == pytest.approx([v, -u, 1.1 - math.pi / 2])
    # 100·0.1² + 100·0.05² + 400·0.02²
    assert pose_graph.edge_chi2(ex=0.1, ey=-0.05, et=0.02, wxy=100, wt=400) == pytest.approx(1.41)
    for n in (3, 4, 9):
        assert pose_graph.hessian_rank(n=n) == 3 * n - 3
    # the two-pose example: pose 1 ends exactly at the measurement, seen from pose 0
    edges = [[0, 1, [1.0, 0.5, 0.6], [[10.0, 1.0, 0.0], [1.0, 10.0, 0.0], [0.0, 0.0, 50.0]]]]
    rel = pose_graph.gauss_newton(poses=[[3, -2, 2], [3.5, -1, 2.8]], edges=edges, iterations=10)
    assert np.allclose(rel, [[0, 0, 0], [1.0, 0.5, 0.6]], atol=1e-9)


def test_intel_figures() -> None:
    """The published and re-measured INTEL numbers (curriculum research, section 5)."""
    graph = intel.intel()
    assert (len(graph.poses), len(graph.edges)) == (1228, 1483)
    assert intel.loop_closures() == 256
    assert intel.degrees_of_freedom() == 768
    assert intel.initial_chi2() == pytest.approx(5149721.04, rel=1e-8)
    # PythonRobotics' notebook, inverted error convention: 7191686.3825 → 215.8405
    assert intel.mistake_initial_chi2_inverse_convention() == pytest.approx(7191686.3825, abs=1e-3)


def test_intel_optimum() -> None:
    assert intel.final_chi2() == pytest.approx(215.8302, abs=1e-4)
    assert intel.mistake_final_chi2_inverse_convention() == pytest.approx(215.8405, abs=1e-4)
    before, after = intel.before_after_demo()
    assert len(before) == len(after) == 1228 and before[0] == after[0]


def test_intel_windows_are_drawn_by_the_whole_capstone() -> None:
    """The fixed seed of intel/optimise-g2o draws both pieces of the real building."""
    from slamcourse.course import reference
    from slamcourse.grading.properties import TrustedCallee, exercise_seed, run

    spec = COURSE.exercise("intel/optimise-g2o")
    opts = spec.options
    ref = reference.function(spec, spec.reference or "", spec.reference_line)
    windows = {intel.intel_window(150, 160), intel.intel_window(1060, 160)}
    outcome = run(
        strategy=get_kind("code").strategy(spec),
        examples=opts.examples,
        signature=opts.signature,
        returns=opts.returns,
        tolerance=opts.tolerance,
        reference=lambda **kw: [[0.0]],  # only the drawn inputs matter here
        call=TrustedCallee(lambda text, iterations: [[0.0]]).call,
        max_examples=opts.max_examples,
        seed=exercise_seed(spec.id),
    )
    assert ref is not None
    assert windows <= {d["text"] for d in outcome.drawn}


# --- 2. enough mutants and variants -----------------------------------------------------------


def test_every_code_exercise_has_enough_mutants_and_variants() -> None:
    for chapter in CHAPTERS:
        folder = ROOT / "exercises" / chapter
        for yaml_path in sorted(folder.glob("*.yaml")):
            if "kind: code" not in yaml_path.read_text(encoding="utf-8"):
                continue
            slug = yaml_path.stem
            mutants = sorted((folder / "mutants" / slug).glob("*.py"))
            variants = sorted((folder / "variants" / slug).glob("*.py"))
            assert len(mutants) >= 8, f"{chapter}/{slug}: {len(mutants)} mutants"
            assert len(variants) >= 3, f"{chapter}/{slug}: {len(variants)} variants"
            for path in mutants:
                assert path.read_text(encoding="utf-8").startswith("# mistake: "), path
            for path in variants:
                assert path.read_text(encoding="utf-8").startswith("# method: "), path
