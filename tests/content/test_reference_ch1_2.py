"""Content tests for chapters 1–2 (``state``, ``observation``).

Three layers:

1. the reference functions agree with values computed independently (by hand, by counting
   array entries, by finite differences);
2. every exercise YAML parses and uses only the keys ``docs/authoring.md`` allows for its kind,
   and the chapters place every exercise exactly once;
3. a small stand-in for ``slamcourse validate`` (written from ``docs/authoring.md``, not from the
   engine): on the canonical and many random variants the parameters satisfy ``require``, the
   reference computes, every template renders, and every misconception is rejected by the
   accepted window and distinguishable from the other misconceptions.
"""

from __future__ import annotations

import importlib.util
import math
from pathlib import Path
from types import ModuleType

import numpy as np
import pytest

jinja2 = pytest.importorskip("jinja2")

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = {
    "state": ROOT / "chapters" / "01-state.md",
    "observation": ROOT / "chapters" / "02-observation.md",
}
EXERCISE_DIRS = {cid: ROOT / "exercises" / cid for cid in CHAPTERS}
RANDOM_VARIANTS = 300


def load_reference(chapter: str) -> ModuleType:
    path = EXERCISE_DIRS[chapter] / "reference.py"
    spec = importlib.util.spec_from_file_location(f"_ref_{chapter}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


state = load_reference("state")
obs = load_reference("observation")


# --- 1. reference functions against independent values -----------------------------------


@pytest.mark.parametrize("num_landmarks", [0, 1, 3, 50, 1000])
def test_state_dimension_counts_pose_and_landmarks(num_landmarks: int) -> None:
    labels = ["x_r", "y_r", "theta_r"] + [
        f"{c}_{j}" for j in range(1, num_landmarks + 1) for c in ("x", "y")
    ]
    assert state.state_dimension(num_landmarks=num_landmarks) == len(labels)


@pytest.mark.parametrize(
    ("num_landmarks", "pose_dim", "landmark_dim"), [(3, 3, 2), (50, 3, 2), (200, 6, 3), (7, 6, 3)]
)
def test_covariance_entries_are_n_squared(
    num_landmarks: int, pose_dim: int, landmark_dim: int
) -> None:
    n = pose_dim + landmark_dim * num_landmarks
    assert (
        state.covariance_entry_count(num_landmarks, pose_dim, landmark_dim) == np.zeros((n, n)).size
    )


@pytest.mark.parametrize("num_landmarks", [1, 10, 500])
def test_unique_entries_count_one_triangle_and_diagonal(num_landmarks: int) -> None:
    n = 3 + 2 * num_landmarks
    assert state.unique_covariance_entries(num_landmarks=num_landmarks) == len(
        np.triu_indices(n)[0]
    )


def test_state_canonical_values_checked_by_hand() -> None:
    assert state.state_dimension(num_landmarks=3) == 9
    assert state.covariance_entry_count(num_landmarks=50) == 103 * 103 == 10609
    assert state.covariance_entry_count(num_landmarks=1000) == 2003 * 2003 == 4_012_009
    assert (
        state.covariance_entry_count(num_landmarks=200, pose_dim=6, landmark_dim=3)
        == 606**2
        == 367_236
    )
    assert state.unique_covariance_entries(num_landmarks=10) == 23 * 24 // 2 == 276
    # the seed's "symmetry saves 253 entries for n = 23" and "~500,000 for n = 1003"
    assert 23**2 - 276 == 253
    assert 1003**2 - state.unique_covariance_entries(num_landmarks=500) == 502_503
    assert state.covariance_growth_factor(few_landmarks=50, many_landmarks=1000) == pytest.approx(
        4_012_009 / 10609
    )
    assert state.landmark_x_index(landmark=2) == 6  # [x_r y_r θ_r x_1 y_1 x_2 ...]


def test_landmark_index_matches_layout() -> None:
    labels = ["x_r", "y_r", "theta_r"] + [f"{c}_{j}" for j in range(1, 41) for c in ("x", "y")]
    for j in range(1, 41):
        assert labels[state.landmark_x_index(landmark=j) - 1] == f"x_{j}"


def test_state_misconceptions_differ_from_answers() -> None:
    for n_lm in range(2, 300):
        right = state.covariance_entry_count(n_lm)
        assert right not in {
            state.mistake_state_size_not_squared(n_lm),
            state.mistake_pose_forgotten_entries(n_lm),
        }
        right3 = state.covariance_entry_count(n_lm, 6, 3)
        assert right3 != state.mistake_planar_sizes_entries(n_lm, 6, 3)


CANONICAL_POSE = (2.0, 3.0, math.pi / 4)
CANONICAL_LANDMARK = (5.0, 7.0)


def test_observation_canonical_values_checked_by_hand() -> None:
    kw = dict(xr=2.0, yr=3.0, thr=math.pi / 4, xj=5.0, yj=7.0)
    assert obs.predicted_range(**kw) == pytest.approx(5.0)  # 3-4-5 triangle
    assert obs.predicted_bearing(**kw) == pytest.approx(math.atan(4 / 3) - math.pi / 4)
    assert obs.predicted_bearing(**kw) == pytest.approx(0.141897, abs=1e-6)
    assert obs.innovation(z_r=5.3, z_b=0.05, h_r=5.0, h_b=0.14) == pytest.approx([0.3, -0.09])
    expected = [[-0.6, -0.8, 0.0, 0.6, 0.8], [4 / 25, -3 / 25, -1.0, -4 / 25, 3 / 25]]
    assert np.allclose(obs.observation_jacobian(**kw), expected)


def test_wrap_angle() -> None:
    assert obs.wrap_angle(math.pi) == pytest.approx(math.pi)
    assert obs.wrap_angle(-math.pi) == pytest.approx(math.pi)
    assert obs.wrap_angle(3 * math.pi / 2) == pytest.approx(-math.pi / 2)
    assert obs.innovation(z_r=1, z_b=-3.1, h_r=1, h_b=3.1)[1] == pytest.approx(2 * math.pi - 6.2)


def test_bearing_is_positive_to_the_left() -> None:
    # robot at the origin facing +y: a landmark on the -x axis is to its left
    assert obs.predicted_bearing(xr=0, yr=0, thr=math.pi / 2, xj=-3, yj=0) == pytest.approx(
        math.pi / 2
    )


def _h(p: np.ndarray) -> np.ndarray:
    return np.asarray(obs.predict_measurement(p[:3], p[3:]))


@pytest.mark.parametrize("seed", range(20))
def test_jacobian_matches_finite_differences(seed: int) -> None:
    rng = np.random.default_rng(seed)
    p = np.concatenate([rng.uniform(-10, 10, 2), rng.uniform(-3, 3, 1), rng.uniform(-10, 10, 2)])
    if math.hypot(p[3] - p[0], p[4] - p[1]) < 1:
        p[3] += 5
    eps = 1e-6
    numeric = np.zeros((2, 5))
    for k in range(5):
        e = np.zeros(5)
        e[k] = eps
        d = _h(p + e) - _h(p - e)
        d[1] = math.remainder(d[1], 2 * math.pi)
        numeric[:, k] = d / (2 * eps)
    analytic = np.array(obs.observation_jacobian(*p))
    assert np.allclose(analytic, numeric, atol=1e-6)
    dx, dy = p[3] - p[0], p[4] - p[1]
    q = dx * dx + dy * dy
    assert obs.d_range_d_xr(np.array(dx), np.array(dy), np.array(q)) == pytest.approx(numeric[0, 0])
    assert obs.d_bearing_d_xr(np.array(dx), np.array(dy), np.array(q)) == pytest.approx(
        numeric[1, 0]
    )


@pytest.mark.parametrize("observed", [1, 2, 3])
def test_nonzero_columns_are_pose_and_observed_landmark(observed: int) -> None:
    first = 3 + 2 * (observed - 1) + 1  # 1-based column of x_observed
    expected = ["c1", "c2", "c3", f"c{first}", f"c{first + 1}"]
    assert obs.nonzero_jacobian_columns(observed=observed, num_landmarks=3) == expected


def test_full_state_jacobian_embeds_the_small_one() -> None:
    x = obs.example_state(3)
    H = obs.numeric_state_jacobian(x, 2)
    small = np.array(obs.observation_jacobian(*x[:3], *x[5:7]))
    assert np.allclose(H[:, [0, 1, 2, 5, 6]], small, atol=1e-6)
    assert np.allclose(H[:, [3, 4, 7, 8]], 0.0)


# --- 2. Canonical answers through the real engine ---------------------------------------
# (Keys, placement, variants and misconceptions are checked by the real validator in
# tests/content/test_bundled_course.py.)


def test_canonical_answers() -> None:
    """The canonical variant of every numeric exercise, as the reference code computes it."""
    from slamcourse.course.loader import load_course
    from slamcourse.course.locate import bundled_course_root
    from slamcourse.course.variants import variant
    from slamcourse.kinds import get_kind

    course = load_course(bundled_course_root())
    got = {}
    for exercise_id in course.exercise_ids:
        spec = course.exercise(exercise_id)
        if spec.chapter in ("state", "observation") and spec.kind not in ("expression", "code"):
            got[exercise_id] = get_kind(spec.kind).expected(spec, variant(spec, 0))
    assert got["state/state-vector-size"] == 9
    assert got["state/landmark-index"] == 6
    assert got["state/covariance-entries"] == 10609
    assert got["state/covariance-growth"] == pytest.approx(378.17, abs=0.01)
    assert got["state/covariance-entries-3d"] == 367_236
    assert got["state/symmetric-unique-entries"] == 276
    assert got["observation/predicted-range"] == pytest.approx(5.0)
    assert got["observation/predicted-bearing"] == pytest.approx(0.1419, abs=1e-4)
    assert got["observation/innovation"] == pytest.approx([0.3, -0.09])
    assert got["observation/jacobian-columns"] == ["c1", "c2", "c3", "c6", "c7"]
    assert np.allclose(
        got["observation/jacobian-matrix"],
        [[-0.6, -0.8, 0, 0.6, 0.8], [0.16, -0.12, -1, -0.16, 0.12]],
    )
