"""Content tests for chapter ``particles``.

1. canonical answers and every figure the prose quotes, pinned by hand or by an independent
   computation;
2. the judged exercise's stated probabilities hold for its test set;
3. every code exercise has enough mutants and correct variants (graded, once, by
   ``test_bundled_course.py``).
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
from slamcourse.grading import testset

ROOT = Path(__file__).resolve().parents[2]
CHAPTER = "particles"
COURSE = load_course(bundled_course_root())
PROSE = (ROOT / "chapters" / "23-particles.md").read_text(encoding="utf-8")


def _reference() -> ModuleType:
    path = ROOT / "exercises" / CHAPTER / "reference.py"
    spec = importlib.util.spec_from_file_location("_ref_particles", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


ref = _reference()


# --- 1. canonical answers and the prose's figures ---------------------------------------------


def test_canonical_answers() -> None:
    # √(0.01·1.2² + 0.02·(0.5² + 0.8²)) = √0.0322
    assert ref.trans_noise_sd(r1=0.5, t=1.2, r2=-0.8, a3=0.01, a4=0.02) == pytest.approx(
        math.sqrt(0.0322)
    )
    # weights 2, 1, 0.5, 0.25, 0.25 of 4: Σw̄² = 0.25 + 0.0625 + 0.015625 + 2·0.00390625
    assert ref.ess(w1=2, w2=1, w3=0.5, w4=0.25, w5=0.25) == pytest.approx(1 / 0.3359375)
    # weights 1 3 2 0 4 (total 10), u = 0.3: thresholds .06 .26 .46 .66 .86 vs .1 .4 .6 .6 1
    assert ref.resampled(w1=1, w2=3, w3=2, w4=0, w5=4, u=0.3) == [0, 1, 2, 4, 4]
    assert ref.fastslam_numbers(m=100, k=50) == 100 * (4 + 300)


def _weights_by_hand(zr, zp, preds, sr, sp):  # type: ignore[no-untyped-def]
    out = []
    for r, p in preds:
        dphi = (zp - p + math.pi) % (2 * math.pi) - math.pi
        out.append(math.exp(-0.5 * ((zr - r) ** 2 / sr**2 + dphi**2 / sp**2)))
    return out[0] / sum(out)


def test_importance_weight_by_hand() -> None:
    kw = dict(zr=4.0, zp=3.11, r1=4.05, p1=-3.13, r2=3.88, p2=3.05, r3=4.1, p3=3.09)
    want = _weights_by_hand(4.0, 3.11, [(4.05, -3.13), (3.88, 3.05), (4.1, 3.09)], 0.1, 0.05)
    assert ref.particle_weight(**kw, sr=0.1, sp=0.05) == pytest.approx(want)


def test_landmark_update_by_the_information_form() -> None:
    mx, my, s, zr, zp, sr, sp = 4.0, 3.0, 0.04, 5.2, math.atan2(3, 4) - 0.05, 0.1, 0.05
    q = mx * mx + my * my
    h = np.array([[mx, my] / np.sqrt(q), [-my / q, mx / q]])
    info = np.eye(2) / s + h.T @ np.diag([1 / sr**2, 1 / sp**2]) @ h
    nu = np.array([zr - math.sqrt(q), zp - math.atan2(my, mx)])
    want = np.array([mx, my]) + np.linalg.solve(info, h.T @ np.diag([1 / sr**2, 1 / sp**2]) @ nu)
    assert ref.landmark_mean(mx=mx, my=my, s=s, zr=zr, zp=zp, sr=sr, sp=sp) == pytest.approx(want)


def test_prose_figures() -> None:
    # multinomial with equal weights: a particle gets no copy with probability (1 − 1/N)^N
    assert f"{(1 - 1 / 100) ** 100:.3f}" == "0.366" and "0.366 for" in PROSE
    assert f"{1 / math.e:.3f}" == "0.368" and "1/e \\approx 0.368" in PROSE
    assert round(100 / math.e) == 37 and "about 37 %" in PROSE
    # N_eff of 2, 1, 0.5, 0.25, 0.25
    assert f"{1 / (0.25 + 0.0625 + 0.015625 + 2 * 0.00390625):.2f}" == "2.98" and "2.98" in PROSE
    # four particles 0.1 0.4 0.3 0.2, u = 0.5: thresholds and survivors
    thresholds = [(0.5 + m) / 4 for m in range(4)]
    assert thresholds == [0.125, 0.375, 0.625, 0.875]
    assert "0.125, 0.375, 0.625, 0.875" in PROSE
    cum = [0.1, 0.5, 0.8, 1.0]
    survivors = [next(i for i, c in enumerate(cum) if c >= t) for t in thresholds]
    assert survivors == [1, 1, 2, 3] and "particles $1, 1, 2, 3$" in PROSE
    # FastSLAM against EKF-SLAM memory, 100 particles and 50 landmarks
    assert 100 * (3 + 1 + 50 * (2 + 4)) == 30400 and "30,400" in PROSE
    assert (3 + 2 * 50) + (3 + 2 * 50) ** 2 == 10712 and "10,712" in PROSE
    assert 2.5 < 30400 / 10712 < 3 and "almost three times" in PROSE
    # the wrapped bearing difference, and the variance taken for a standard deviation
    assert abs((3.11 + 3.13 + math.pi) % (2 * math.pi) - math.pi) == pytest.approx(0.0432, abs=1e-3)
    assert "0.04$ rad, not by $6.24" in PROSE
    assert math.sqrt(0.01) == pytest.approx(10 * 0.01)
    # the judge: nine tests, 1e-6 per call
    assert ref.pf.TESTS == 9 and "Nine such tests" in PROSE and "10^{-6}" in PROSE


# --- 2. the judged exercise's probabilities ---------------------------------------------------


def test_sample_motion_states_its_probabilities_truly() -> None:
    spec = COURSE.exercise("particles/sample-motion")
    tests = testset.build(spec)
    calls = len(tests.cases)
    assert calls <= 200, "the prompt says at most 200 calls"
    assert calls * ref.PER_CALL <= ref.WHOLE_CHECK == 2e-4
    assert "at most $10^{-6}$" in spec.prompt.source
    assert "at most 200 calls" in spec.prompt.source and "2 \\times 10^{-4}" in spec.prompt.source
    # the tails the domain excludes: a negative drive (8σ) or turning noise past ±π (π/0.4 σ),
    # for up to 2000 samples of three controls, stay far below the 1 % left of the budget
    tail = 2000 * (math.erfc(8 / math.sqrt(2)) / 2 + 2 * math.erfc(math.pi / 0.4 / math.sqrt(2)))
    assert tail < 0.01 * ref.PER_CALL


# --- 3. mutants and variants ------------------------------------------------------------------
# Each is graded through the real sandbox once, by the course's validation
# (test_bundled_course.py::test_exercise_is_sound: mutants fail, variants pass); here, only that
# there are enough of them.


def test_every_code_exercise_has_enough_mutants_and_variants() -> None:
    folder = ROOT / "exercises" / CHAPTER
    for yaml_path in sorted(folder.glob("*.yaml")):
        if "kind: code" not in yaml_path.read_text(encoding="utf-8"):
            continue
        slug = yaml_path.stem
        mutants = sorted((folder / "mutants" / slug).glob("*.py"))
        variants = sorted((folder / "variants" / slug).glob("*.py"))
        assert len(mutants) >= 8, f"{slug}: {len(mutants)} mutants"
        assert len(variants) >= 3, f"{slug}: {len(variants)} variants"
        for path in mutants:
            assert path.read_text(encoding="utf-8").startswith("# mistake: "), path
        for path in variants:
            assert path.read_text(encoding="utf-8").startswith("# method: "), path
