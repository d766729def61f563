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
import re
from pathlib import Path
from types import ModuleType
from typing import Any

import numpy as np
import pytest
import yaml

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


# --- 2. YAML keys and chapter placement ----------------------------------------------------

COMMON_KEYS = {
    "format",
    "id",
    "kind",
    "title",
    "prompt",
    "parameters",
    "require",
    "reference",
    "tolerance",
    "hints",
    "explanation",
    "misconceptions",
    "tags",
}
KIND_KEYS = {
    "number": {"exact", "angle", "units"},
    "vector": {"angle", "exact", "units"},
    "matrix": {"angle", "exact", "units"},
    "expression": {"variables", "points"},
    "choice": {"choices", "shuffle"},
    "multi": {"choices", "shuffle"},
    "order": {"items", "feedback"},
    "line": {"code", "language", "answer", "lines"},
}
REQUIRED = {"format", "id", "kind", "title", "prompt", "explanation"}
PARAM_SPEC_KEYS = {"canonical", "int", "uniform", "round", "choice", "value", "expr"}
NUMERIC_KINDS = {"number", "vector", "matrix", "expression"}


def exercise_files() -> list[Path]:
    return sorted(p for d in EXERCISE_DIRS.values() for p in d.glob("*.yaml"))


def load(path: Path) -> dict[str, Any]:
    data = yaml.safe_load(path.read_text(encoding="utf-8"))
    assert isinstance(data, dict), path
    return data


@pytest.mark.parametrize("path", exercise_files(), ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_yaml_uses_only_documented_keys(path: Path) -> None:
    data = load(path)
    assert data.keys() >= REQUIRED
    assert data["kind"] in KIND_KEYS
    unknown = data.keys() - COMMON_KEYS - KIND_KEYS[data["kind"]]
    assert not unknown, f"unknown keys {unknown}"
    assert data["format"] == 1
    assert data["id"] == f"{path.parent.name}/{path.stem}"
    for name, spec in (data.get("parameters") or {}).items():
        assert isinstance(spec, dict) and spec.keys() <= PARAM_SPEC_KEYS, name
    if "tolerance" in data:
        assert data["tolerance"].keys() <= {"rtol", "atol"}
    for m in data.get("misconceptions", []):
        assert m.keys() == {"id", "compute", "message"}
    for c in data.get("choices", []):
        assert c.keys() <= {"id", "text", "correct", "feedback"}
    for item in data.get("items", []):
        assert item.keys() == {"id", "text"}
    for spec in (data.get("variables") or {}).values():
        assert spec.keys() <= {"uniform", "expr"}
    hints = data.get("hints", [])
    assert 2 <= len(hints) <= 3
    if data["kind"] in NUMERIC_KINDS:
        assert "reference" in data
    ref = load_reference(path.parent.name)
    for fn in [data.get("reference")] + [m["compute"] for m in data.get("misconceptions", [])]:
        if fn is not None:
            assert callable(getattr(ref, fn, None)), fn


FENCE = re.compile(r"^```\{exercise\}\s+(\S+)\s*$", re.MULTILINE)


@pytest.mark.parametrize("chapter", list(CHAPTERS))
def test_chapter_places_every_exercise_once(chapter: str) -> None:
    text = CHAPTERS[chapter].read_text(encoding="utf-8")
    front = re.match(r"^---\n(.*?)\n---\n", text, re.DOTALL)
    assert front is not None
    meta = yaml.safe_load(front.group(1))
    assert meta.keys() <= {"id", "title", "summary"} and meta["id"] == chapter and meta["title"]
    placed = FENCE.findall(text)
    assert len(placed) == len(set(placed))
    assert set(placed) == {f"{chapter}/{p.stem}" for p in EXERCISE_DIRS[chapter].glob("*.yaml")}
    prose_words = len(FENCE.sub("", text[front.end() :]).split())
    assert 400 <= prose_words <= 900


# --- 3. a stand-in validator over many variants ---------------------------------------------

SAFE = {
    "pi": math.pi,
    "e": math.e,
    "sqrt": math.sqrt,
    "exp": math.exp,
    "log": math.log,
    "log10": math.log10,
    "sin": math.sin,
    "cos": math.cos,
    "tan": math.tan,
    "asin": math.asin,
    "acos": math.acos,
    "atan": math.atan,
    "atan2": math.atan2,
    "hypot": math.hypot,
    "abs": abs,
    "floor": math.floor,
    "ceil": math.ceil,
    "min": min,
    "max": max,
}


def evaluate(expr: Any, names: dict[str, Any]) -> Any:
    if not isinstance(expr, str):
        return expr
    return eval(expr.replace("^", "**"), {"__builtins__": {}}, {**SAFE, **names})


def draw(data: dict[str, Any], variant: int) -> dict[str, Any]:
    specs = data.get("parameters") or {}
    rng = np.random.default_rng([variant, sum(map(ord, data["id"]))])
    for _ in range(1000):
        values: dict[str, Any] = {}
        for name, spec in specs.items():
            if "value" in spec:
                v = spec["value"]
            elif "expr" in spec:
                v = evaluate(spec["expr"], values)
            elif variant == 0:
                v = evaluate(spec["canonical"], values)
            elif "int" in spec:
                v = int(rng.integers(spec["int"][0], spec["int"][1] + 1))
            elif "uniform" in spec:
                v = float(rng.uniform(*spec["uniform"]))
            else:
                v = spec["choice"][int(rng.integers(len(spec["choice"])))]
            if "round" in spec and variant != 0:
                v = round(v, spec["round"])
            values[name] = v
        if all(evaluate(r, values) for r in data.get("require", [])):
            return values
        assert variant != 0, "the canonical variant violates require"
    raise AssertionError("require cannot be satisfied")


def _num(x: Any, digits: int | None = None) -> str:
    x = float(x)
    if digits is not None:
        return f"{x:.{digits}f}"
    return str(round(x)) if x == round(x) and abs(x) < 1e15 else f"{x:.4g}"


def _angle(x: Any) -> str:
    for k in (1, 2, 3, 4, 6, 8, 12):
        m = float(x) * k / math.pi
        if m != 0 and abs(m - round(m)) < 1e-9:
            return f"{round(m)}π/{k}".replace("1π", "π").replace("/1", "")
    return _num(x)


def _vec(v: Any) -> str:
    return "[" + ", ".join(_num(a) for a in v) + "]"


def _mat(m: Any) -> str:
    return (
        r"\begin{bmatrix}"
        + r" \\ ".join(" & ".join(_num(a) for a in row) for row in m)
        + r"\end{bmatrix}"
    )


ENV = jinja2.Environment(undefined=jinja2.StrictUndefined)
ENV.filters.update(num=_num, angle=_angle, vec=_vec, mat=_mat)


def render(template: str, names: dict[str, Any]) -> str:
    text = ENV.from_string(template).render(**names)
    assert "{{" not in text and "{%" not in text
    return text


def accepted(answer: Any, reference: Any, data: dict[str, Any]) -> bool:
    tol = {"rtol": 0.01, "atol": 1e-9, **data.get("tolerance", {})}
    a = np.asarray(answer, dtype=float)
    b = np.asarray(reference, dtype=float)
    if a.shape != b.shape:
        return False
    if data.get("exact"):
        return bool(np.all(a == b))
    diff = a - b
    angle = data.get("angle")
    if angle is True:
        diff = np.vectorize(lambda d: math.remainder(d, 2 * math.pi))(diff)
    elif isinstance(angle, list):
        flat = diff.reshape(-1)
        for i in angle:
            flat[i] = math.remainder(flat[i], 2 * math.pi)
    return bool(np.all(np.abs(diff) <= tol["atol"] + tol["rtol"] * np.abs(b)))


def sample_points(data: dict[str, Any], count: int, seed: int) -> dict[str, np.ndarray]:
    rng = np.random.default_rng(seed)
    values: dict[str, np.ndarray] = {}
    for name, spec in data["variables"].items():
        if "uniform" in spec:
            values[name] = rng.uniform(*spec["uniform"], size=count)
        else:
            values[name] = eval(spec["expr"].replace("^", "**"), {"__builtins__": {}}, {**values})
    return values


@pytest.mark.parametrize("path", exercise_files(), ids=lambda p: f"{p.parent.name}/{p.stem}")
def test_variants_render_and_misconceptions_are_rejected(path: Path) -> None:
    data = load(path)
    ref = load_reference(path.parent.name)
    kind = data["kind"]
    texts = [data["prompt"], data["explanation"], *data.get("hints", [])]
    texts += [m["message"] for m in data.get("misconceptions", [])]

    if kind == "expression":
        names = sample_points(data, data.get("points", 50), 0)
        right = getattr(ref, data["reference"])(**names)
        for m in data.get("misconceptions", []):
            wrong = getattr(ref, m["compute"])(**names)
            assert not accepted(wrong, right, {**data, "angle": None}), m["id"]
            for other in data["misconceptions"]:
                if other is not m:
                    assert not accepted(wrong, getattr(ref, other["compute"])(**names), data)
        for t in texts:
            render(t, {"answer": None})
        return

    for variant in [0, *range(1, 1 + (RANDOM_VARIANTS if data.get("parameters") else 0))]:
        params = draw(data, variant)
        answer = getattr(ref, data["reference"])(**params) if "reference" in data else None
        for t in texts:
            render(t, {**params, "answer": answer})
        if kind in NUMERIC_KINDS:
            assert accepted(answer, answer, data)
            if data.get("exact"):
                assert float(answer) == int(answer)
            wrongs = {
                m["id"]: getattr(ref, m["compute"])(**params)
                for m in data.get("misconceptions", [])
            }
            for mid, wrong in wrongs.items():
                assert not accepted(wrong, answer, data), f"variant {variant}: {mid} is accepted"
                assert not accepted(answer, wrong, data), f"variant {variant}: answer matches {mid}"
                for oid, other in wrongs.items():
                    if oid != mid:
                        assert not accepted(wrong, other, data), f"variant {variant}: {mid} ~ {oid}"
        elif kind in ("choice", "multi"):
            ids = [c["id"] for c in data["choices"]]
            assert len(ids) == len(set(ids))
            for c in data["choices"]:
                render(c["text"], params)
                render(c.get("feedback", ""), params)
            correct = (
                answer
                if answer is not None
                else [c["id"] for c in data["choices"] if c.get("correct")]
            )
            correct = [correct] if isinstance(correct, str) else list(correct)
            assert correct and set(correct) <= set(ids)
            if kind == "choice":
                assert len(correct) == 1
        elif kind == "order":
            ids = [i["id"] for i in data["items"]]
            assert len(ids) == len(set(ids)) >= 3
            assert set(data.get("feedback", {})) <= set(ids)


def test_canonical_answers() -> None:
    """The canonical variant of every exercise, as the reference code computes it."""
    got = {}
    for path in exercise_files():
        data = load(path)
        if "reference" in data and data["kind"] != "expression":
            params = draw(data, 0)
            got[data["id"]] = getattr(load_reference(path.parent.name), data["reference"])(**params)
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
