"""Content tests for the filter chapters beyond the lesson: ``ekf-slam``, ``jcbb``, ``consistency``.

1. canonical answers pinned to values derived here by hand, independently of the reference code;
2. every code exercise ships ≥ 8 mutants (``exercises/<chapter>/mutants/<slug>/NN-name.py``,
   first line ``# mistake: …``) and ≥ 3 variants (``variants/<slug>/NN-name.py``, first line
   ``# method: …``). That each mutant is rejected and each variant accepted in the real sandbox
   is checked once, by ``test_bundled_course.py::test_exercise_is_sound``.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = tuple(
    c for c in ("ekf-slam", "jcbb", "consistency") if (ROOT / "exercises" / c).is_dir()
)


def load_reference(chapter: str) -> ModuleType:
    path = ROOT / "exercises" / chapter / "reference.py"
    name = f"_ref_filters_{chapter.replace('-', '_')}"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


# --- 1. canonical answers ---------------------------------------------------------------------


def test_ekf_slam_canonical_answers() -> None:
    ref = load_reference("ekf-slam")
    # K = p / (p + r) = 0.04 / 0.05
    assert ref.scalar_gain(var_prior=0.04, var_meas=0.01) == pytest.approx(0.8)
    assert ref.scalar_posterior(var_prior=0.04, var_meas=0.01) == pytest.approx(0.008)
    # P⁺_yy = P_yy − P_xy² / (P_xx + R) = 0.09 − 0.0009 / 0.06
    assert ref.correlated_update(pxx=0.04, pxy=0.03, pyy=0.09, rxx=0.02) == pytest.approx(0.075)
    # 4 m along θ + φ = 0.8 rad from (2, 1)
    assert ref.landmark_position(x=2, y=1, t=0.5, rng=4, brg=0.3) == pytest.approx(
        [2 + 4 * math.cos(0.8), 1 + 4 * math.sin(0.8)]
    )
    # across ±π: ν = −3.08 − 3.05 + 2π, θ⁺ = 3.05 + 0.8ν − 2π
    nu = -3.08 - 3.05 + 2 * math.pi
    got = ref.heading_update(theta=3.05, var_t=0.04, compass=-3.08, var_c=0.01)
    assert got == pytest.approx(3.05 + 0.8 * nu - 2 * math.pi)
    # n = 9: (n + 2)² − n² = 121 − 81
    assert ref.new_entries(landmarks=3) == 40
    # G_r P_rr with a = 0.7: rows [P_xx − r s P_xθ, 0, P_xθ − r s P_θθ], [r c P_xθ, P_yy, r c P_θθ]
    s, c = math.sin(0.7), math.cos(0.7)
    expected = [
        [0.04 - 5 * s * 0.005, 0, 0.005 - 5 * s * 0.01],
        [5 * c * 0.005, 0.03, 5 * c * 0.01],
    ]
    got = ref.cross_covariance(t=0.3, rng=5, brg=0.4, vx=0.04, vy=0.03, vt=0.01, cxt=0.005)
    assert np.allclose(got, expected)


def test_ekf_slam_code_references_by_hand() -> None:
    ref = load_reference("ekf-slam")
    # straight ahead from heading 0: G_r = [[1, 0, 0], [0, 1, r]], G_z = diag(1, r)
    a, b, t, r, sr, sb = 0.04, 0.03, 0.01, 5.0, 0.09, 0.0004
    out = np.asarray(
        ref.augment(mu=[0, 0, 0], P=np.diag([a, b, t]), z=[r, 0.0], R=np.diag([sr, sb]))
    )
    assert out.shape == (5, 5)
    assert np.allclose(out[3:, :3], [[a, 0, 0], [0, b, r * t]])
    assert np.allclose(out[3:, 3:], [[a + sr, 0], [0, b + r * r * t + r * r * sb]])
    # a direct measurement of one coordinate of a 2-D state: (P⁻¹ + Hᵀ R⁻¹ H)⁻¹ by hand
    p = np.array([[0.04, 0.03], [0.03, 0.09]])
    got = np.asarray(ref.update_covariance(P=p, H=[[1.0, 0.0]], R=[[0.02]]))
    assert np.allclose(
        got,
        [[0.04 - 0.04**2 / 0.06, 0.03 - 0.04 * 0.03 / 0.06], [0.03 - 0.04 * 0.03 / 0.06, 0.075]],
    )


def test_jcbb_canonical_answers() -> None:
    ref = load_reference("jcbb")
    from scipy.stats import chi2

    # S⁻¹ = [[s2, −c], [−c, s1]] / (s1 s2 − c²):
    # (0.01·0.025 − 2·0.02·0.008 + 0.0064·0.025) / 0.000225
    assert ref.pair_d2(nu1=-0.1, nu2=-0.08, s1=0.025, s2=0.025, c=0.02) == pytest.approx(0.4)
    assert ref.mistake_pair_sum_individual(
        nu1=-0.1, nu2=-0.08, s1=0.025, s2=0.025, c=0.02
    ) == pytest.approx(0.656)
    # two laser pairings and one camera bearing: 5 degrees of freedom
    assert ref.mixed_gate(full=2, bearing_only=1, confidence=0.95) == pytest.approx(
        chi2.ppf(0.95, 5), rel=1e-9
    )
    assert ref.scene_greedy_choice() == "c"  # both measurements with A
    # the scene's right hypothesis, innovations (0, −0.1, 0, −0.1): well inside χ²₄ = 9.49
    h = [[-1, 0, 0, 1, 0, 0, 0], [0, -0.1, -1, 0, 0.1, 0, 0]]
    h += [[-10 / math.hypot(10, 1.2), -1.2 / math.hypot(10, 1.2), 0, 0, 0, 0, 0]]
    h[2][5:] = [10 / math.hypot(10, 1.2), 1.2 / math.hypot(10, 1.2)]
    h += [[1.2 / 101.44, -10 / 101.44, -1, 0, 0, -1.2 / 101.44, 10 / 101.44]]
    p = np.diag([0.01, 0.01, 0.02, 0.01, 0.01, 0.01, 0.01])
    r = np.diag([0.04, 0.0004])
    nu = [0, -0.1, 0, -0.1]
    s = np.array(h) @ p @ np.array(h).T + np.kron(np.eye(2), r)
    assert ref.joint_d2(H=h, P=p, R=r, nu=nu) == pytest.approx(nu @ np.linalg.inv(s) @ nu)
    assert ref.joint_compatible(H=h, P=p, R=r, nu=nu, confidence=0.95) is True
    # five times the shift: d² = 25 × 0.49 ≈ 12.3 > 9.49 (one heading error of 0.5 rad is too much)
    assert ref.joint_compatible(H=h, P=p, R=r, nu=[5 * v for v in nu], confidence=0.95) is False
    assert ref.scene_choice() == "a"  # z1–A, z2–B


def test_jcbb_scene_figures_shown_in_prompts_come_from_the_scene() -> None:
    import yaml

    ref = load_reference("jcbb")
    z1, z2 = ref.scene_measurements()
    jointly = yaml.safe_load((ROOT / "exercises/jcbb/scene-jcbb.yaml").read_text("utf-8"))
    shown = {k: v["value"] for k, v in jointly["parameters"].items()}
    for key, pairing in {"d_ab": (0, 1), "d_ba": (1, 0), "d_aa": (0, 0), "d_0a": (-1, 0)}.items():
        assert shown[key] == pytest.approx(ref.scene_d2(pairing), abs=1e-4), key
    greedy = yaml.safe_load((ROOT / "exercises/jcbb/scene-greedy.yaml").read_text("utf-8"))
    shown = {k: v["value"] for k, v in greedy["parameters"].items()}
    assert [shown["z1r"], shown["z1b"]] == pytest.approx(z1, abs=1e-4)
    assert [shown["z2r"], shown["z2b"]] == pytest.approx(z2, abs=1e-4)
    for key, pairing in {"d11": (0, -1), "d12": (1, -1), "d21": (-1, 0), "d22": (-1, 1)}.items():
        assert shown[key] == pytest.approx(ref.scene_d2(pairing), abs=1e-4), key


def test_consistency_canonical_answers() -> None:
    ref = load_reference("consistency")
    from scipy.stats import chi2

    # e = (0.3, −0.4), P = [[0.09, 0.02], [0.02, 0.16]], det = 0.0140:
    # (0.09·0.16 − 2·0.02·0.3·(−0.4) + 0.16·0.09) / 0.014 = (0.0144 + 0.0048 + 0.0144) / 0.014
    got = ref.nees_value(xt=2.3, yt=1.1, xh=2.0, yh=1.5, pxx=0.09, pxy=0.02, pyy=0.16)
    assert got == pytest.approx(0.0336 / 0.014)
    assert ref.mistake_nees_euclidean(
        xt=2.3, yt=1.1, xh=2.0, yh=1.5, pxx=0.09, pxy=0.02, pyy=0.16
    ) == pytest.approx(0.25)
    band = ref.anees_band(dof=3, runs=50, confidence=0.95)
    assert band == pytest.approx([chi2.ppf(0.025, 150) / 50, chi2.ppf(0.975, 150) / 50], rel=1e-8)
    # 4.6 × n = 9.2 is far above [χ²_100(0.025), χ²_100(0.975)] / 50 ≈ [1.48, 2.59]
    assert ref.diagnosis(dof=2, runs=50, ratio=4.6, anees=9.2) == "b"
    assert ref.diagnosis(dof=2, runs=50, ratio=1.0, anees=2.0) == "a"
    assert ref.diagnosis(dof=3, runs=20, ratio=0.5, anees=1.5) == "c"
    # a heading error across ±π: e = (−0.1, 0.1, 6.2 wrapped to 6.2 − 2π ≈ −0.083)
    e = np.array([-0.1, 0.1, 6.2 - 2 * math.pi])
    p = np.array([[0.04, 0.01, 0.0], [0.01, 0.04, 0.0], [0.0, 0.0, 0.01]])
    got = ref.nees(x_true=[1.0, 2.0, 3.1], x_hat=[1.1, 1.9, -3.1], P=p.tolist())
    assert got == pytest.approx(e @ np.linalg.inv(p) @ e)


def test_figures_quoted_in_the_consistency_chapter_come_from_the_library() -> None:
    from slamcourse.slam import consistency

    text = " ".join((ROOT / "chapters" / "14-consistency.md").read_text(encoding="utf-8").split())

    def shown(value: float, digits: int) -> str:
        return f"{value:.{digits}f}"

    low, high = consistency.average_band(2, 50)
    assert f"$[{shown(low, 2)}, {shown(high, 2)}]$" in text
    low, high = consistency.average_band(2, 1)
    assert f"$[{shown(low, 2)}, {shown(high, 2)}]$" in text
    low, high = consistency.average_band(3, 1)
    assert f"between {shown(low, 2)} and {shown(high, 2)}" in text
    for scale, mean, inside in ((1.0, "1.97", "39 of the 40"), (0.1, "9.3", "only 2 of its 40")):
        anees = consistency.simulate_anees(scale, runs=50, steps=40, seed=0)
        digits = len(mean.split(".")[1])
        assert shown(float(anees.mean()), digits) == mean
        count = sum(consistency.diagnose(a, 2, 50) == "consistent" for a in anees)
        assert f"{count} of" in inside and inside in text
    pessimistic = consistency.simulate_anees(10.0, runs=50, steps=40, seed=0)
    assert shown(float(pessimistic.mean()), 1) == "1.2" and "about 1.2" in text
    assert all(consistency.diagnose(a, 2, 50) != "over-confident" for a in pessimistic)


# --- 2. enough mutants and variants -----------------------------------------------------------


def _code_slugs(chapter: str) -> list[str]:
    folder = ROOT / "exercises" / chapter
    return [
        p.stem
        for p in sorted(folder.glob("*.yaml"))
        if "\nkind: code\n" in p.read_text(encoding="utf-8")
    ]


def test_every_code_exercise_has_enough_mutants_and_variants() -> None:
    assert "ekf-slam" in CHAPTERS
    for chapter in CHAPTERS:
        folder = ROOT / "exercises" / chapter
        slugs = _code_slugs(chapter)
        assert slugs, chapter
        for slug in slugs:
            mutants = sorted((folder / "mutants" / slug).glob("*.py"))
            variants = sorted((folder / "variants" / slug).glob("*.py"))
            assert len(mutants) >= 8, f"{chapter}/{slug}: {len(mutants)} mutants"
            assert len(variants) >= 3, f"{chapter}/{slug}: {len(variants)} variants"
            for path in mutants:
                assert path.read_text(encoding="utf-8").startswith("# mistake: "), path
            for path in variants:
                assert path.read_text(encoding="utf-8").startswith("# method: "), path
