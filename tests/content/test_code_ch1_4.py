"""Content tests for the code exercises of chapters 1–4 (state, observation, association, drift).

1. Learner-style attempts graded through the real sandbox: several *correct* implementations
   written differently (pure Python, numpy, wrapped or unwrapped angles, list / tuple / array
   returns) must pass, and common *wrong* ones must fail with the misconception named.
2. Every misconception of these exercises also fails on Hypothesis' *generated* inputs alone
   (without the explicit examples), so a learner's mistake is caught even off the edge cases.
3. The reference functions reproduce the lesson's figures, with the seed's wrong ones corrected.
"""

from __future__ import annotations

import importlib.util
import math
import re
import textwrap
from collections.abc import Iterator
from types import ModuleType
from typing import Any, cast

import numpy as np
import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.kinds import get_kind
from slamcourse.kinds.code import CodeKind
from slamcourse.verdict import Verdict

COURSE = load_course(bundled_course_root())
ROOT = bundled_course_root()
KIND = cast(CodeKind, get_kind("code"))


def grade(exercise_id: str, source: str) -> Verdict:
    spec = COURSE.exercise(exercise_id)
    return KIND.check_source(spec, textwrap.dedent(source), "attempt.py")


# --- 1. learner attempts through the sandbox ------------------------------------------------

P, F = "passed", "failed"

CASES: list[tuple[str, str, str, str, str | None]] = [
    # ---------------------------------------------------------------- state/state-size
    (
        "state/state-size",
        "tuple",
        """
        def state_size(pose_dim, landmark_dim, num_landmarks):
            n = pose_dim + landmark_dim * num_landmarks
            return (n, n * n)
        """,
        P,
        None,
    ),
    (
        "state/state-size",
        "numpy-ints-list",
        """
        import numpy as np
        def state_size(p, l, k):
            n = np.int64(p) + np.int64(l) * k
            return [n, n ** 2]
        """,
        P,
        None,
    ),
    (
        "state/state-size",
        "floats",
        """
        def state_size(pose_dim, landmark_dim, num_landmarks):
            n = float(pose_dim + landmark_dim * num_landmarks)
            return n, n * n
        """,
        P,
        None,
    ),
    (
        "state/state-size",
        "pose-forgotten",
        """
        def state_size(pose_dim, landmark_dim, num_landmarks):
            n = landmark_dim * num_landmarks
            return n, n * n
        """,
        F,
        "pose-forgotten",
    ),
    (
        "state/state-size",
        "unique-entries",
        """
        def state_size(pose_dim, landmark_dim, num_landmarks):
            n = pose_dim + landmark_dim * num_landmarks
            return n, n * (n + 1) // 2
        """,
        F,
        "unique-entries",
    ),
    # ---------------------------------------------------------- observation/observation-model
    (
        "observation/observation-model",
        "math-unwrapped",
        """
        import math
        def observation_model(xr, yr, thr, xj, yj):
            return math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr) - thr
        """,
        P,
        None,
    ),
    (
        "observation/observation-model",
        "numpy-wrapped-array",
        """
        import numpy as np
        def observation_model(xr, yr, thr, xj, yj):
            d = np.array([xj - xr, yj - yr])
            b = np.arctan2(d[1], d[0]) - thr
            b = (b + np.pi) % (2 * np.pi) - np.pi
            return np.array([np.linalg.norm(d), b])
        """,
        P,
        None,
    ),
    (
        "observation/observation-model",
        "sqrt-atan2-wrap-list",
        """
        from math import atan2, cos, sin, sqrt
        def observation_model(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            b = atan2(dy, dx) - thr
            return [sqrt(dx ** 2 + dy ** 2), atan2(sin(b), cos(b))]
        """,
        P,
        None,
    ),
    (
        "observation/observation-model",
        "degrees",
        """
        import math
        def observation_model(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            return math.hypot(dx, dy), math.degrees(math.atan2(dy, dx) - thr)
        """,
        F,
        "degrees",
    ),
    (
        "observation/observation-model",
        "heading-ignored",
        """
        import math
        def observation_model(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            return math.hypot(dx, dy), math.atan2(dy, dx)
        """,
        F,
        "heading-ignored",
    ),
    (
        "observation/observation-model",
        "atan",
        """
        import math
        def observation_model(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            return math.hypot(dx, dy), math.atan(dy / dx) - thr
        """,
        F,
        "atan-quadrant",
    ),
    (
        "observation/observation-model",
        "squared-range",
        """
        import math
        def observation_model(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            return dx * dx + dy * dy, math.atan2(dy, dx) - thr
        """,
        F,
        "squared-range",
    ),
    # ---------------------------------------------------------------- observation/jacobian
    (
        "observation/jacobian",
        "analytic-numpy",
        """
        import numpy as np
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            q = dx * dx + dy * dy
            r = np.sqrt(q)
            lm = np.array([[dx / r, dy / r], [-dy / q, dx / q]])
            return np.hstack([-lm, np.array([[0.0], [-1.0]]), lm])
        """,
        P,
        None,
    ),
    (
        "observation/jacobian",
        "own-finite-differences",
        """
        import math
        import numpy as np
        def h(v):
            xr, yr, thr, xj, yj = v
            return np.array([math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr) - thr])
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            x = np.array([xr, yr, thr, xj, yj], dtype=float)
            J = np.zeros((2, 5))
            for k in range(5):
                e = np.zeros(5)
                e[k] = 1e-6
                d = h(x + e) - h(x - e)
                d[1] = math.atan2(math.sin(d[1]), math.cos(d[1]))
                J[:, k] = d / 2e-6
            return J
        """,
        P,
        None,
    ),
    (
        "observation/jacobian",
        "tuple-of-tuples",
        """
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            q = dx ** 2 + dy ** 2
            r = q ** 0.5
            return ((-dx / r, -dy / r, 0, dx / r, dy / r), (dy / q, -dx / q, -1, -dy / q, dx / q))
        """,
        P,
        None,
    ),
    (
        "observation/jacobian",
        "landmark-signs-flipped",
        """
        import math
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            q = dx * dx + dy * dy
            r = math.sqrt(q)
            return [[-dx / r, -dy / r, 0.0, -dx / r, -dy / r],
                    [dy / q, -dx / q, -1.0, dy / q, -dx / q]]
        """,
        F,
        "landmark-signs-flipped",
    ),
    (
        "observation/jacobian",
        "heading-plus-one",
        """
        import math
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            q = dx * dx + dy * dy
            r = math.sqrt(q)
            return [[-dx / r, -dy / r, 0.0, dx / r, dy / r],
                    [dy / q, -dx / q, 1.0, -dy / q, dx / q]]
        """,
        F,
        "heading-plus-one",
    ),
    (
        "observation/jacobian",
        "range-over-q",
        """
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            dx, dy = xj - xr, yj - yr
            q = dx * dx + dy * dy
            return [[-dx / q, -dy / q, 0.0, dx / q, dy / q],
                    [dy / q, -dx / q, -1.0, -dy / q, dx / q]]
        """,
        F,
        "range-without-sqrt",
    ),
    # FD without wrapping the bearing jumps by 2π/h behind the robot: wrong, no named mistake
    (
        "observation/jacobian",
        "fd-unwrapped",
        """
        import math
        def range_bearing_jacobian(xr, yr, thr, xj, yj):
            def h(v):
                return [math.hypot(v[3] - v[0], v[4] - v[1]),
                        math.atan2(v[4] - v[1], v[3] - v[0]) - v[2]]
            x = [xr, yr, thr, xj, yj]
            J = [[0.0] * 5 for _ in range(2)]
            for k in range(5):
                up, down = list(x), list(x)
                up[k] += 1e-6
                down[k] -= 1e-6
                for i in range(2):
                    J[i][k] = (h(up)[i] - h(down)[i]) / 2e-6
            return J
        """,
        F,
        None,
    ),
    # ---------------------------------------------------------------- association/mahalanobis
    (
        "association/mahalanobis",
        "pure",
        """
        def mahalanobis(nu0, nu1, s00, s11):
            return nu0 ** 2 / s00 + nu1 ** 2 / s11
        """,
        P,
        None,
    ),
    (
        "association/mahalanobis",
        "numpy-solve",
        """
        import numpy as np
        def mahalanobis(nu0, nu1, s00, s11):
            nu = np.array([nu0, nu1])
            S = np.diag([s00, s11])
            return nu @ np.linalg.solve(S, nu)
        """,
        P,
        None,
    ),
    (
        "association/mahalanobis",
        "whitened",
        """
        import math
        def mahalanobis(nu0, nu1, s00, s11):
            return math.hypot(nu0 / math.sqrt(s00), nu1 / math.sqrt(s11)) ** 2
        """,
        P,
        None,
    ),
    (
        "association/mahalanobis",
        "euclidean",
        """
        def mahalanobis(nu0, nu1, s00, s11):
            return nu0 * nu0 + nu1 * nu1
        """,
        F,
        "euclidean",
    ),
    (
        "association/mahalanobis",
        "times-s",
        """
        def mahalanobis(nu0, nu1, s00, s11):
            return nu0 * s00 * nu0 + nu1 * s11 * nu1
        """,
        F,
        "multiplied-by-s",
    ),
    (
        "association/mahalanobis",
        "square-root",
        """
        import math
        def mahalanobis(nu0, nu1, s00, s11):
            return math.sqrt(nu0 ** 2 / s00 + nu1 ** 2 / s11)
        """,
        F,
        "square-root",
    ),
    # ---------------------------------------------------------------- association/chi2-gate
    (
        "association/chi2-gate",
        "closed-forms",
        """
        import math
        from statistics import NormalDist
        def in_gate(d2, dof, confidence):
            if dof == 2:
                return d2 < -2 * math.log(1 - confidence)
            return d2 < NormalDist().inv_cdf((1 + confidence) / 2) ** 2
        """,
        P,
        None,
    ),
    (
        "association/chi2-gate",
        "bisection-numpy-bool",
        """
        import math
        import numpy as np
        def cdf(x, k):
            if k == 1:
                return math.erf(math.sqrt(x / 2))
            return 1 - math.exp(-x / 2)
        def in_gate(d2, dof, confidence):
            lo, hi = 0.0, 100.0
            for _ in range(60):
                mid = (lo + hi) / 2
                if cdf(mid, dof) < confidence:
                    lo = mid
                else:
                    hi = mid
            return np.float64(d2) < np.float64(lo)
        """,
        P,
        None,
    ),
    (
        "association/chi2-gate",
        "one-dof",
        """
        from statistics import NormalDist
        def in_gate(d2, dof, confidence):
            return d2 < NormalDist().inv_cdf((1 + confidence) / 2) ** 2
        """,
        F,
        "one-dof",
    ),
    (
        "association/chi2-gate",
        "gate-on-d",
        """
        import math
        from statistics import NormalDist
        def in_gate(d2, dof, confidence):
            if dof == 2:
                threshold = -2 * math.log(1 - confidence)
            else:
                threshold = NormalDist().inv_cdf((1 + confidence) / 2) ** 2
            return math.sqrt(d2) < threshold
        """,
        F,
        "gate-on-distance",
    ),
    # ------------------------------------------------------- association/nearest-neighbour-fix
    (
        "association/nearest-neighbour-fix",
        "fixed-loop",
        """
        def nearest_neighbour(z, landmarks, s00, s11, gate):
            best, best_d2 = -1, float("inf")
            for j, h in enumerate(landmarks):
                d2 = (z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11
                if d2 < gate and d2 < best_d2:
                    best, best_d2 = j, d2
            return best
        """,
        P,
        None,
    ),
    (
        "association/nearest-neighbour-fix",
        "numpy-argmin",
        """
        import numpy as np
        def nearest_neighbour(z, landmarks, s00, s11, gate):
            if len(landmarks) == 0:
                return -1
            nu = np.asarray(z, dtype=float) - np.asarray(landmarks, dtype=float)
            d2 = (nu ** 2 / np.array([s00, s11])).sum(axis=1)
            j = np.argmin(d2)
            return j if d2[j] < gate else -1
        """,
        P,
        None,
    ),
    (
        "association/nearest-neighbour-fix",
        "wrapped-bearing",
        """
        import math
        def nearest_neighbour(z, landmarks, s00, s11, gate):
            scored = []
            for j, (r, b) in enumerate(landmarks):
                db = math.atan2(math.sin(z[1] - b), math.cos(z[1] - b))
                scored.append(((z[0] - r) ** 2 / s00 + db ** 2 / s11, j))
            inside = [s for s in scored if s[0] < gate]
            return min(inside)[1] if inside else -1
        """,
        P,
        None,
    ),
    (
        "association/nearest-neighbour-fix",
        "gate-ignored",
        """
        def nearest_neighbour(z, landmarks, s00, s11, gate):
            best, best_d2 = -1, float("inf")
            for j, h in enumerate(landmarks):
                d2 = (z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11
                if d2 < best_d2:
                    best, best_d2 = j, d2
            return best
        """,
        F,
        "gate-ignored",
    ),
    (
        "association/nearest-neighbour-fix",
        "first-in-gate",
        """
        def nearest_neighbour(z, landmarks, s00, s11, gate):
            for j, h in enumerate(landmarks):
                if (z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11 < gate:
                    return j
            return -1
        """,
        F,
        "first-in-gate",
    ),
    # ---------------------------------------------------------------- drift/random-walk
    (
        "drift/random-walk",
        "math",
        """
        import math
        def random_walk_error(sigma, steps):
            return sigma * math.sqrt(steps)
        """,
        P,
        None,
    ),
    (
        "drift/random-walk",
        "numpy-variance-sum",
        """
        import numpy as np
        def random_walk_error(sigma, steps):
            return np.sqrt(np.sum(np.full(steps, sigma ** 2)))
        """,
        P,
        None,
    ),
    (
        "drift/random-walk",
        "systematic",
        """
        def random_walk_error(sigma, steps):
            return sigma * steps
        """,
        F,
        "systematic",
    ),
    (
        "drift/random-walk",
        "variance",
        """
        def random_walk_error(sigma, steps):
            return steps * sigma ** 2
        """,
        F,
        "variance",
    ),
    # ---------------------------------------------------------------- drift/heading-drift
    (
        "drift/heading-drift",
        "loop",
        """
        import math
        def lateral_drift(step_length, heading_rate, steps):
            y = 0.0
            heading = 0.0
            for _ in range(steps):
                heading += heading_rate
                y += step_length * math.sin(heading)
            return y
        """,
        P,
        None,
    ),
    (
        "drift/heading-drift",
        "numpy",
        """
        import numpy as np
        def lateral_drift(step_length, heading_rate, steps):
            k = np.arange(1, steps + 1)
            return step_length * np.sin(heading_rate * k).sum()
        """,
        P,
        None,
    ),
    (
        "drift/heading-drift",
        "closed-form-unguarded",  # divides by sin(0) for a perfect heading (rate 0)
        """
        import math
        def lateral_drift(step_length, heading_rate, steps):
            a, n = heading_rate, steps
            return step_length * math.sin(n * a / 2) * math.sin((n + 1) * a / 2) / math.sin(a / 2)
        """,
        F,
        None,
    ),
    (
        "drift/heading-drift",
        "small-angle",
        """
        def lateral_drift(step_length, heading_rate, steps):
            return sum(step_length * heading_rate * k for k in range(1, steps + 1))
        """,
        F,
        "small-angle",
    ),
    (
        "drift/heading-drift",
        "from-zero",
        """
        import math
        def lateral_drift(step_length, heading_rate, steps):
            return sum(step_length * math.sin(heading_rate * k) for k in range(steps))
        """,
        F,
        "starts-at-zero",
    ),
    (
        "drift/heading-drift",
        "final-heading",
        """
        import math
        def lateral_drift(step_length, heading_rate, steps):
            return steps * step_length * math.sin(heading_rate * steps)
        """,
        F,
        "final-heading",
    ),
]


@pytest.mark.parametrize(
    ("exercise_id", "source", "status", "misconception"),
    [pytest.param(ex, src, st, mis, id=f"{ex}:{label}") for ex, label, src, st, mis in CASES],
)
def test_attempt(exercise_id: str, source: str, status: str, misconception: str | None) -> None:
    verdict = grade(exercise_id, source)
    assert verdict.status == status, verdict.feedback
    assert verdict.misconception == misconception, verdict.feedback


def test_every_code_exercise_is_covered() -> None:
    code_ids = {
        ex
        for ex in COURSE.exercise_ids
        if ex.split("/")[0] in {"state", "observation", "association", "drift"}
        and COURSE.exercise(ex).kind == "code"
    }
    assert code_ids == {ex for ex, *_ in CASES}


def test_fix_starter_is_the_listing_and_fails_as_euclidean() -> None:
    spec = COURSE.exercise("association/nearest-neighbour-fix")
    starter = spec.options.starter.read_text(encoding="utf-8")
    listing = COURSE.exercise("association/nearest-neighbour-bug").options.code
    body = [line for line in starter.splitlines() if line.startswith("    ") and '"""' not in line]
    assert all(line.strip() in starter for line in listing.splitlines())
    assert body[-1].strip() == "return best_index"
    verdict = grade("association/nearest-neighbour-fix", starter)
    assert verdict.misconception == "euclidean"


# --- 2. misconceptions fail on generated inputs alone --------------------------------------


def _code_specs() -> Iterator[Any]:
    for ex in COURSE.exercise_ids:
        if ex.split("/")[0] in {"state", "observation", "association", "drift"}:
            spec = COURSE.exercise(ex)
            if spec.kind == "code":
                for m in spec.misconceptions:
                    yield pytest.param(ex, m.id, id=f"{ex}:{m.id}")


@pytest.mark.parametrize(("exercise_id", "misconception"), list(_code_specs()))
def test_misconception_fails_on_generated_inputs(exercise_id: str, misconception: str) -> None:
    from slamcourse.course import reference
    from slamcourse.grading.properties import TrustedCallee, exercise_seed, run

    spec = COURSE.exercise(exercise_id)
    opts = spec.options
    m = next(m for m in spec.misconceptions if m.id == misconception)
    wrong = reference.function(spec, m.function or "", m.line)
    outcome = run(
        strategy=KIND.strategy(spec),
        examples=(),
        signature=opts.signature,
        returns=opts.returns,
        tolerance=opts.tolerance,
        reference=reference.function(spec, spec.reference or "", spec.reference_line),
        call=TrustedCallee(wrong).call,
        max_examples=opts.max_examples,
        seed=exercise_seed(spec.id),
    )
    assert not outcome.passed


# --- 3. reference figures ------------------------------------------------------------------


def load_reference(chapter: str) -> ModuleType:
    path = ROOT / "exercises" / chapter / "reference.py"
    spec = importlib.util.spec_from_file_location(f"_ref4_{chapter}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_lesson_figures() -> None:
    state, obs = load_reference("state"), load_reference("observation")
    assoc, drift = load_reference("association"), load_reference("drift")
    assert state.state_size(3, 2, 3) == (9, 81)
    assert state.state_size(3, 2, 0) == (3, 9)
    r, b = obs.observation_model(2, 3, math.pi / 4, 5, 7)
    assert r == pytest.approx(5.0) and b == pytest.approx(math.atan2(4, 3) - math.pi / 4)
    assert assoc.mahalanobis_scalar(0.5, 0.25) == pytest.approx(1.0)
    assert assoc.mahalanobis(0.3, -0.09, 0.25, 0.01) == pytest.approx(1.17)
    assert assoc.chi2_threshold(1, 0.95) == pytest.approx(3.841, abs=1e-3)
    assert assoc.chi2_threshold(2, 0.95) == pytest.approx(5.991, abs=1e-3)
    assert drift.systematic_drift(0.1, 100) == pytest.approx(10.0)
    assert drift.random_walk_error(0.05, 400) == pytest.approx(1.0)
    assert drift.square_loop_error(0.02, 100) == pytest.approx(0.0, abs=1e-9)
    # The lesson claims 24.5 m; the exact sum is 23.195 m (the small-angle sum is 25.25 m).
    assert drift.lateral_drift(0.5, 0.01, 100) == pytest.approx(23.195, abs=1e-3)
    assert drift.lateral_drift_small_angle(0.5, 0.01, 100) == pytest.approx(25.25)


@pytest.mark.parametrize("point", [(2, 3, 0.785, 5, 7), (1, 2, 0, -2, 2), (0, 0, 3.1, -0.4, 0.5)])
def test_fd_jacobian_matches_analytic(point: tuple[float, ...]) -> None:
    obs = load_reference("observation")
    fd = obs.range_bearing_jacobian(*point)
    assert np.allclose(fd, obs.observation_jacobian(*point), rtol=1e-7, atol=1e-8)


FENCE = re.compile(r"^```\{exercise\}\s+(\S+)\s*$", re.MULTILINE)


@pytest.mark.parametrize("chapter", ["association", "drift"])
def test_new_chapters_place_their_exercises(chapter: str) -> None:
    path = next((ROOT / "chapters").glob(f"*-{chapter}.md"))
    text = path.read_text(encoding="utf-8")
    placed = FENCE.findall(text)
    assert len(placed) == len(set(placed))
    folder = ROOT / "exercises" / chapter
    assert set(placed) == {f"{chapter}/{p.stem}" for p in folder.glob("*.yaml")}
    prose = FENCE.sub("", text.split("---", 2)[2])
    assert len(prose.split()) >= 800  # a complete chapter, to the depth of chapters 1-2
