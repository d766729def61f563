"""Content tests for the code exercises of chapters 5–8 (``graph``, ``vision``,
``factor-graphs``, ``occupancy``).

1. the reference functions reproduce figures worked out by hand (the lesson's numbers, after
   checking them: several figures in the source text were wrong);
2. learner-style implementations are graded through the real sandbox, as ``slamcourse check``
   does: correct ones written in different styles (loops or numpy, lists or tuples or arrays,
   ``solve`` or ``inv``) pass, and the common wrong ones fail with the misconception named.
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
COURSE = load_course(bundled_course_root())


def grade(exercise_id: str, source: str):
    spec = COURSE.exercise(exercise_id)
    return get_kind("code").check_source(spec, source, "attempt.py")


def load_reference(chapter: str) -> ModuleType:
    path = ROOT / "exercises" / chapter / "reference.py"
    spec = importlib.util.spec_from_file_location(f"_ref58_{chapter.replace('-', '_')}", path)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


graph = load_reference("graph")
vision = load_reference("vision")
fg = load_reference("factor-graphs")
occ = load_reference("occupancy")


# --- 1. reference figures ----------------------------------------------------------------------


def test_lesson_information_matrix_and_its_solution() -> None:
    omega = graph.build_omega(3, [(0, 1, 1.0), (1, 2, 1.0), (0, 2, 1.0)])
    omega[0, 0] += 10  # the prior on x0
    assert omega.tolist() == [[12, -1, -1], [-1, 2, -1], [-1, -1, 2]]
    assert np.count_nonzero(omega) == 9
    mu = graph.solve_information(omega.tolist(), [10, 1, 3])
    # the lesson claimed [1.4, 2.0, 2.6]; Ω times that is [10.2, 0, 1.8], not ξ
    assert mu == pytest.approx([1.4, 46 / 15, 56 / 15])
    assert omega @ mu == pytest.approx([10, 1, 3])


def test_chain_information_matrix_is_tridiagonal() -> None:
    omega = graph.build_omega(6, [(k, k + 1, 2.0) for k in range(5)])
    assert np.count_nonzero(omega) == 6 + 2 * 5
    assert omega.sum(axis=1) == pytest.approx(np.zeros(6))  # edges fix only relative positions


@pytest.mark.parametrize(("w", "s", "n"), [(0.5, 5, 146), (0.8, 5, 12), (0.5, 8, 1177)])
def test_ransac_iteration_counts(w: float, s: int, n: int) -> None:
    assert vision.ransac_iterations(inlier_ratio=w, sample_size=s, confidence=0.99) == n
    # n samples reach the confidence, n - 1 do not
    assert 1 - (1 - w**s) ** n >= 0.99 > 1 - (1 - w**s) ** (n - 1)


def test_lesson_epipolar_residual() -> None:
    E = [[0, -1, 0], [1, 0, -0.5], [0, 0.3, 0]]
    assert vision.epipolar_residual(E, [0.5, 0.3, 1], [0.6, 0.2, 1]) == pytest.approx(-0.09)
    assert vision.mistake_epipolar_transposed(E, [0.5, 0.3, 1], [0.6, 0.2, 1]) == pytest.approx(
        -0.01
    )


def test_essential_matrix_satisfies_the_epipolar_constraint() -> None:
    rng = np.random.default_rng(3)
    for _ in range(20):
        R = vision.rotation_from_quaternion(rng.normal(size=4))
        assert np.allclose(R @ R.T, np.eye(3))
        assert np.linalg.det(R) == pytest.approx(1)
        t = rng.normal(size=3)
        X = rng.normal(size=3) + np.array([0.0, 0.0, 5.0])  # a point in front of camera 1
        X2 = R @ X + t  # the same point in camera 2's frame
        x, x2 = X / X[2], X2 / X2[2]
        E = vision.essential_matrix(t, R.tolist())
        assert vision.epipolar_residual(E, x, x2) == pytest.approx(0, abs=1e-9)
        assert vision.skew(t) @ X == pytest.approx(np.cross(t, X))


def test_fill_in_by_hand() -> None:
    chain = [(0, 1), (1, 2), (2, 3), (3, 4)]
    assert fg.fill_in(5, chain, [0, 1, 2, 3, 4]) == 0
    assert fg.fill_in(5, chain, [2, 0, 1, 3, 4]) == 1
    for k in range(1, 8):
        star = [(0, leaf) for leaf in range(1, k + 1)]
        assert fg.fill_in(k + 1, star, list(range(k + 1))) == k * (k - 1) // 2
        assert fg.fill_in(k + 1, star, [*range(1, k + 1), 0]) == 0
        assert fg.star_fill_in(leaves=k) == k * (k - 1) // 2


def test_log_odds_figures() -> None:
    l1, p1 = occ.log_odds_update(0, 0.9)
    assert (l1, p1) == pytest.approx((math.log(9), 0.9))
    l2, p2 = occ.log_odds_update(l1, 0.3)
    assert l2 == pytest.approx(1.3499, abs=1e-4) and p2 == pytest.approx(27 / 34)
    # the lesson said about 2.6 more free readings would bring the cell back to 0.5; it is 1.59
    assert l2 / -occ.log_odds(0.3) == pytest.approx(1.5932, abs=1e-4)
    # 0.7-readings needed to pass 0.95: 4
    assert math.ceil(occ.log_odds(0.95) / occ.log_odds(0.7)) == 4


def test_ray_update_by_hand() -> None:
    assert occ.update_ray([0, 0, 0, 0], 2, 0.85, -0.4) == pytest.approx([-0.4, -0.4, 0.85, 0])
    assert occ.update_ray([1.0], 0, 0.85, -0.4) == pytest.approx([1.85])


# --- 2. grading learner code in the sandbox ---------------------------------------------------

OK = "passed"
WRONG = "failed"

BUILD_OMEGA = {
    "loops-lists": """
def build_omega(n, edges):
    O = [[0.0] * n for _ in range(n)]
    for i, j, w in edges:
        O[i][i] += w
        O[j][j] += w
        O[i][j] -= w
        O[j][i] -= w
    return O
""",
    "incidence-numpy": """
import numpy as np

def build_omega(n, edges):
    if not edges:
        return np.zeros((n, n))
    A = np.zeros((len(edges), n))
    w = np.array([e[2] for e in edges], dtype=float)
    for k, (i, j, _) in enumerate(edges):
        A[k, i], A[k, j] = -1.0, 1.0
    return A.T @ np.diag(w) @ A
""",
    "tuple-of-tuples": """
def build_omega(n, edges):
    cells = {}
    for e in edges:
        i, j, w = e[0], e[1], e[2]
        for key, v in (((i, i), w), ((j, j), w), ((i, j), -w), ((j, i), -w)):
            cells[key] = cells.get(key, 0) + v
    return tuple(tuple(cells.get((r, c), 0) for c in range(n)) for r in range(n))
""",
    "flat-like-the-js": """
def build_omega(n, edges):
    O = [0.0] * (n * n)
    for i, j, w in edges:
        O[i * n + i] += w
        O[j * n + j] += w
        O[i * n + j] -= w
        O[j * n + i] -= w
    return O
""",
    "no-off-diagonal": """
import numpy as np

def build_omega(n, edges):
    O = np.zeros((n, n))
    for i, j, w in edges:
        O[i, i] += w
        O[j, j] += w
    return O
""",
    "plus-off-diagonal": """
import numpy as np

def build_omega(n, edges):
    O = np.zeros((n, n))
    for i, j, w in edges:
        O[i, i] += w
        O[j, j] += w
        O[i, j] += w
        O[j, i] += w
    return O
""",
    "upper-only": """
import numpy as np

def build_omega(n, edges):
    O = np.zeros((n, n))
    for i, j, w in edges:
        a, b = min(i, j), max(i, j)
        O[a, a] += w
        O[b, b] += w
        O[a, b] -= w
    return O
""",
    "assigned": """
def build_omega(n, edges):
    O = [[0.0] * n for _ in range(n)]
    for i, j, w in edges:
        O[i][i] = w
        O[j][j] = w
        O[i][j] = -w
        O[j][i] = -w
    return O
""",
}

SOLVE_INFORMATION = {
    "solve": """
import numpy as np

def solve_information(omega, xi):
    return np.linalg.solve(omega, xi)
""",
    "inverse": """
import numpy as np

def solve_information(omega, xi):
    return list(np.linalg.inv(np.array(omega)) @ np.array(xi))
""",
    "cholesky": """
import numpy as np

def solve_information(omega, xi):
    L = np.linalg.cholesky(np.asarray(omega, dtype=float))
    y = np.linalg.solve(L, np.asarray(xi, dtype=float))
    return np.linalg.solve(L.T, y)
""",
    "gauss-by-hand": """
def solve_information(omega, xi):
    n = len(xi)
    A = [list(map(float, row)) + [float(b)] for row, b in zip(omega, xi)]
    for c in range(n):
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            A[r] = [a - f * p for a, p in zip(A[r], A[c])]
    mu = [0.0] * n
    for r in reversed(range(n)):
        mu[r] = (A[r][n] - sum(A[r][k] * mu[k] for k in range(r + 1, n))) / A[r][r]
    return tuple(mu)
""",
    "diagonal-only": """
def solve_information(omega, xi):
    return [xi[i] / omega[i][i] for i in range(len(xi))]
""",
    "multiplied": """
import numpy as np

def solve_information(omega, xi):
    return np.array(omega) @ np.array(xi)
""",
}

RANSAC_ITERATIONS = {
    "ceil": """
import math

def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.ceil(math.log(1 - confidence) / math.log(1 - inlier_ratio ** sample_size))
""",
    "numpy-float": """
import numpy as np

def ransac_iterations(w, s, p):
    return np.ceil(np.log1p(-p) / np.log1p(-np.power(w, s)))
""",
    "search-loop": """
def ransac_iterations(inlier_ratio, sample_size, confidence):
    clean = 1.0
    for _ in range(sample_size):
        clean *= inlier_ratio
    n, miss = 0, 1.0
    while 1 - miss < confidence:
        n += 1
        miss *= 1 - clean
    return n
""",
    "rounded": """
import math

def ransac_iterations(inlier_ratio, sample_size, confidence):
    return round(math.log(1 - confidence) / math.log(1 - inlier_ratio ** sample_size))
""",
    "floored": """
import math

def ransac_iterations(inlier_ratio, sample_size, confidence):
    return int(math.log(1 - confidence) / math.log(1 - inlier_ratio ** sample_size))
""",
    "outlier-ratio": """
import math

def ransac_iterations(inlier_ratio, sample_size, confidence):
    eps = 1 - inlier_ratio
    return math.ceil(math.log(1 - confidence) / math.log(1 - eps ** sample_size))
""",
    "no-exponent": """
import math

def ransac_iterations(inlier_ratio, sample_size, confidence):
    return math.ceil(math.log(1 - confidence) / math.log(1 - inlier_ratio))
""",
}

EPIPOLAR = {
    "numpy": """
import numpy as np

def epipolar_residual(E, x, x2):
    return float(np.array(x2) @ np.array(E) @ np.array(x))
""",
    "einsum": """
import numpy as np

def epipolar_residual(E, x, x2):
    return np.einsum("i,ik,k->", x2, E, x)
""",
    "loops": """
def epipolar_residual(E, x, x2):
    total = 0.0
    for i in range(3):
        for k in range(3):
            total += x2[i] * E[i][k] * x[k]
    return total
""",
    "transposed": """
import numpy as np

def epipolar_residual(E, x, x2):
    return np.dot(x, np.dot(E, x2))
""",
}

ESSENTIAL = {
    "skew-numpy": """
import numpy as np

def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]], dtype=float)
    return S @ np.asarray(R)
""",
    "cross-columns": """
import numpy as np

def essential_matrix(t, R):
    return np.cross(t, np.asarray(R).T).T
""",
    "pure-lists": """
def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]

def essential_matrix(t, R):
    cols = [cross(t, [R[0][k], R[1][k], R[2][k]]) for k in range(3)]
    return [[cols[k][i] for k in range(3)] for i in range(3)]
""",
    "wrong-order": """
import numpy as np

def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]])
    return np.asarray(R) @ S
""",
    "skew-sign": """
import numpy as np

def essential_matrix(t, R):
    tx, ty, tz = t
    S = np.array([[0, tz, -ty], [-tz, 0, tx], [ty, -tx, 0]])
    return S @ np.asarray(R)
""",
    "cross-rows": """
import numpy as np

def essential_matrix(t, R):
    return np.cross(t, R)
""",
}

BEST_LINE = {
    "loops": (ROOT / "exercises/vision/solutions/best_line.py").read_text(),
    "numpy": """
import numpy as np

def best_line(points, samples, threshold):
    P = np.asarray(points, dtype=float)
    counts = []
    for a, b in samples:
        d = P[b] - P[a]
        n = np.array([-d[1], d[0]]) / np.linalg.norm(d)
        counts.append(int(np.sum(np.abs((P - P[a]) @ n) < threshold)))
    return int(np.argmax(counts))
""",
    "max-with-key": """
import math

def inliers(points, a, b, threshold):
    ax, ay = points[a]
    bx, by = points[b]
    L = math.dist(points[a], points[b])
    return sum(abs((bx - ax) * (y - ay) - (by - ay) * (x - ax)) / L < threshold
               for x, y in points)

def best_line(points, samples, threshold):
    return max(range(len(samples)), key=lambda k: inliers(points, *samples[k], threshold))
""",
    "sample-only": (ROOT / "exercises/vision/starters/best_line.py").read_text(),
    "vertical-distance": """
def best_line(points, samples, threshold):
    best, best_count = 0, -1
    for k, (a, b) in enumerate(samples):
        (x1, y1), (x2, y2) = points[a], points[b]
        m = (y2 - y1) / (x2 - x1)
        c = y1 - m * x1
        count = sum(abs(y - (m * x + c)) < threshold for x, y in points)
        if count > best_count:
            best, best_count = k, count
    return best
""",
    "returns-count": """
import numpy as np

def best_line(points, samples, threshold):
    P = np.asarray(points, dtype=float)
    best = 0
    for a, b in samples:
        d = P[b] - P[a]
        n = np.array([-d[1], d[0]]) / np.linalg.norm(d)
        best = max(best, int(np.sum(np.abs((P - P[a]) @ n) < threshold)))
    return best
""",
}

FILL_IN = {
    "sets": (ROOT / "exercises/factor-graphs/solutions/fill_in.py").read_text(),
    "edge-set": """
from itertools import combinations

def fill_in(n, edges, order):
    E = {frozenset(e) for e in edges}
    alive = set(range(n))
    added = 0
    for v in order:
        nb = sorted(u for u in alive if u != v and frozenset((u, v)) in E)
        for a, b in combinations(nb, 2):
            if frozenset((a, b)) not in E:
                E.add(frozenset((a, b)))
                added += 1
        alive.discard(v)
    return added
""",
    "adjacency-matrix": """
import numpy as np

def fill_in(n, edges, order):
    A = np.zeros((n, n), dtype=bool)
    for a, b in edges:
        A[a, b] = A[b, a] = True
    before = A.sum() // 2
    total_added = 0
    for v in order:
        nb = np.flatnonzero(A[v])
        block = A[np.ix_(nb, nb)]
        total_added += (len(nb) * (len(nb) - 1) // 2) - block.sum() // 2
        A[np.ix_(nb, nb)] = True
        A[nb, nb] = False
        A[v, :] = False
        A[:, v] = False
    return int(total_added)
""",
    "all-pairs": """
def fill_in(n, edges, order):
    nb = [set() for _ in range(n)]
    for a, b in edges:
        nb[a].add(b); nb[b].add(a)
    count = 0
    for v in order:
        rest = sorted(nb[v])
        for i, a in enumerate(rest):
            for b in rest[i + 1:]:
                count += 1
                nb[a].add(b); nb[b].add(a)
        for u in rest:
            nb[u].discard(v)
        nb[v] = set()
    return count
""",
    "kept-eliminated": """
def fill_in(n, edges, order):
    nb = [set() for _ in range(n)]
    for a, b in edges:
        nb[a].add(b); nb[b].add(a)
    count = 0
    for v in order:
        rest = sorted(nb[v])
        for i, a in enumerate(rest):
            for b in rest[i + 1:]:
                if b not in nb[a]:
                    count += 1
                    nb[a].add(b); nb[b].add(a)
    return count
""",
    "not-added": """
def fill_in(n, edges, order):
    nb = [set() for _ in range(n)]
    for a, b in edges:
        nb[a].add(b); nb[b].add(a)
    count = 0
    for v in order:
        rest = sorted(nb[v])
        for i, a in enumerate(rest):
            for b in rest[i + 1:]:
                if b not in nb[a]:
                    count += 1
        for u in rest:
            nb[u].discard(v)
        nb[v] = set()
    return count
""",
}

LOG_ODDS = {
    "math": """
import math

def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return l, 1 / (1 + math.exp(-l))
""",
    "numpy-list": """
import numpy as np

def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + np.log(sensor_prob) - np.log1p(-sensor_prob)
    odds = np.exp(l)
    return [l, odds / (1 + odds)]
""",
    "log-p": """
import math

def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob)
    return l, 1 / (1 + math.exp(-l))
""",
    "multiplied": """
import math

def log_odds_update(current_log_odds, sensor_prob):
    p = 1 / (1 + math.exp(-current_log_odds)) * sensor_prob
    return math.log(p / (1 - p)), p
""",
    "unnormalised": """
import math

def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return l, math.exp(l)
""",
}

RAY = {
    "branches": (ROOT / "exercises/occupancy/solutions/update_ray.py").read_text(),
    "numpy": """
import numpy as np

def update_ray(log_odds, hit_index, l_occ, l_free):
    out = np.array(log_odds, dtype=float)
    out[:hit_index] += l_free
    out[hit_index] += l_occ
    return out
""",
    "in-place": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    for k in range(hit_index):
        log_odds[k] += l_free
    log_odds[hit_index] += l_occ
    return log_odds
""",
    "slices-tuple": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    before = [v + l_free for v in log_odds[:hit_index]]
    return tuple(before + [log_odds[hit_index] + l_occ] + list(log_odds[hit_index + 1:]))
""",
    "beyond-free": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    return [v + (l_occ if k == hit_index else l_free) for k, v in enumerate(log_odds)]
""",
    "hit-not-updated": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    return [v + l_free if k < hit_index else v for k, v in enumerate(log_odds)]
""",
    "hit-as-free": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index + 1):
        out[k] += l_free
    return out
""",
    "overwritten": """
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index):
        out[k] = l_free
    out[hit_index] = l_occ
    return out
""",
}

CASES = [
    # (exercise id, source, expected status, expected misconception)
    ("graph/build-omega", BUILD_OMEGA["loops-lists"], OK, None),
    ("graph/build-omega", BUILD_OMEGA["incidence-numpy"], OK, None),
    ("graph/build-omega", BUILD_OMEGA["tuple-of-tuples"], OK, None),
    ("graph/build-omega", BUILD_OMEGA["flat-like-the-js"], WRONG, None),
    ("graph/build-omega", BUILD_OMEGA["no-off-diagonal"], WRONG, "no-off-diagonal"),
    ("graph/build-omega", BUILD_OMEGA["plus-off-diagonal"], WRONG, "plus-off-diagonal"),
    ("graph/build-omega", BUILD_OMEGA["upper-only"], WRONG, "upper-only"),
    ("graph/build-omega", BUILD_OMEGA["assigned"], WRONG, "assigned"),
    ("graph/solve-information", SOLVE_INFORMATION["solve"], OK, None),
    ("graph/solve-information", SOLVE_INFORMATION["inverse"], OK, None),
    ("graph/solve-information", SOLVE_INFORMATION["cholesky"], OK, None),
    ("graph/solve-information", SOLVE_INFORMATION["gauss-by-hand"], OK, None),
    ("graph/solve-information", SOLVE_INFORMATION["diagonal-only"], WRONG, "diagonal-only"),
    ("graph/solve-information", SOLVE_INFORMATION["multiplied"], WRONG, "multiplied"),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["ceil"], OK, None),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["numpy-float"], OK, None),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["search-loop"], OK, None),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["rounded"], WRONG, "rounded"),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["floored"], WRONG, "floored"),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["outlier-ratio"], WRONG, "outlier-ratio"),
    ("vision/ransac-iterations", RANSAC_ITERATIONS["no-exponent"], WRONG, "no-exponent"),
    ("vision/epipolar-residual", EPIPOLAR["numpy"], OK, None),
    ("vision/epipolar-residual", EPIPOLAR["einsum"], OK, None),
    ("vision/epipolar-residual", EPIPOLAR["loops"], OK, None),
    ("vision/epipolar-residual", EPIPOLAR["transposed"], WRONG, "transposed"),
    ("vision/essential-from-pose", ESSENTIAL["skew-numpy"], OK, None),
    ("vision/essential-from-pose", ESSENTIAL["cross-columns"], OK, None),
    ("vision/essential-from-pose", ESSENTIAL["pure-lists"], OK, None),
    ("vision/essential-from-pose", ESSENTIAL["wrong-order"], WRONG, "wrong-order"),
    ("vision/essential-from-pose", ESSENTIAL["skew-sign"], WRONG, "skew-sign"),
    ("vision/essential-from-pose", ESSENTIAL["cross-rows"], WRONG, "cross-rows"),
    ("vision/ransac-fix", BEST_LINE["loops"], OK, None),
    ("vision/ransac-fix", BEST_LINE["numpy"], OK, None),
    ("vision/ransac-fix", BEST_LINE["max-with-key"], OK, None),
    ("vision/ransac-fix", BEST_LINE["sample-only"], WRONG, "sample-only"),
    ("vision/ransac-fix", BEST_LINE["vertical-distance"], WRONG, "vertical-distance"),
    ("vision/ransac-fix", BEST_LINE["returns-count"], WRONG, "returns-count"),
    ("factor-graphs/fill-in", FILL_IN["sets"], OK, None),
    ("factor-graphs/fill-in", FILL_IN["edge-set"], OK, None),
    ("factor-graphs/fill-in", FILL_IN["adjacency-matrix"], OK, None),
    ("factor-graphs/fill-in", FILL_IN["all-pairs"], WRONG, "all-pairs"),
    ("factor-graphs/fill-in", FILL_IN["kept-eliminated"], WRONG, "kept-eliminated"),
    ("factor-graphs/fill-in", FILL_IN["not-added"], WRONG, "not-added"),
    ("occupancy/log-odds-update", LOG_ODDS["math"], OK, None),
    ("occupancy/log-odds-update", LOG_ODDS["numpy-list"], OK, None),
    ("occupancy/log-odds-update", LOG_ODDS["log-p"], WRONG, "log-p"),
    ("occupancy/log-odds-update", LOG_ODDS["multiplied"], WRONG, "multiplied"),
    ("occupancy/log-odds-update", LOG_ODDS["unnormalised"], WRONG, "unnormalised"),
    ("occupancy/ray-update", RAY["branches"], OK, None),
    ("occupancy/ray-update", RAY["numpy"], OK, None),
    # the prompt says: do not change `log_odds`, return a new list or array
    ("occupancy/ray-update", RAY["in-place"], WRONG, None),
    ("occupancy/ray-update", RAY["slices-tuple"], OK, None),
    ("occupancy/ray-update", RAY["beyond-free"], WRONG, "beyond-free"),
    ("occupancy/ray-update", RAY["hit-not-updated"], WRONG, "hit-not-updated"),
    ("occupancy/ray-update", RAY["hit-as-free"], WRONG, "hit-as-free"),
    ("occupancy/ray-update", RAY["overwritten"], WRONG, "overwritten"),
]


def _case_id(case: tuple[str, str, str, str | None]) -> str:
    exercise, source = case[0], case[1]
    for table in (
        BUILD_OMEGA,
        SOLVE_INFORMATION,
        RANSAC_ITERATIONS,
        EPIPOLAR,
        ESSENTIAL,
        BEST_LINE,
        FILL_IN,
        LOG_ODDS,
        RAY,
    ):
        for name, text in table.items():
            if text is source:
                return f"{exercise.split('/')[1]}-{name}"
    return exercise


@pytest.mark.parametrize(
    ("exercise_id", "source", "expected_status", "expected_misconception"),
    CASES,
    ids=[_case_id(c) for c in CASES],
)
def test_learner_code_is_graded(
    exercise_id: str, source: str, expected_status: str, expected_misconception: str | None
) -> None:
    verdict = grade(exercise_id, source)
    assert verdict.status == expected_status, verdict.feedback
    assert verdict.misconception == expected_misconception, verdict.feedback


# Each exercise's shipped solution (passes) and starter (does not) are graded through the real
# sandbox once, by the course's validation (test_bundled_course.py::test_exercise_is_sound).


# --- 3. the numeric exercises on the lesson's own numbers ------------------------------------

CANONICAL = [
    # (exercise id, answer, passes, misconception)
    ("graph/omega-entry", "12", True, None),
    ("graph/omega-entry", "2", False, "no-prior"),
    ("graph/omega-nonzeros", "9", True, None),
    ("graph/omega-nonzeros", "7", False, "no-loop"),
    ("graph/solve-estimate", "[1.4, 3.0667, 3.7333]", True, None),
    ("graph/solve-estimate", "[1.4, 2.0, 2.6]", False, None),  # the lesson's figure
    ("graph/solve-estimate", "[0.8333, 0.5, 1.5]", False, "diagonal-only"),
    ("graph/chain-sparsity", "0.2998", True, None),
    ("vision/ransac-count", "146", True, None),
    ("vision/ransac-count", "145", False, "floored"),
    ("vision/five-point", "5", True, None),
    ("vision/five-point", "8", False, "eight-point"),
    ("vision/epipolar-value", "-0.09", True, None),
    ("vision/epipolar-value", "-0.01", False, "transposed"),
    ("vision/stereo-scale", "[2, 0, 1.5]", True, None),
    ("factor-graphs/factor-count", "[11, 8]", True, None),
    ("factor-graphs/constraint-dof", "700", True, None),
    ("factor-graphs/constraint-dof", "400", False, "unknowns"),
    ("factor-graphs/star-fill-in", "6", True, None),
    ("factor-graphs/star-fill-in", "12", False, "ordered-pairs"),
    # variant 0 shows the steps relabelled in a shuffled order: a b c d e is never right
    ("factor-graphs/slam-steps", "c e b d a", True, None),
    ("factor-graphs/slam-steps", "a b c d e", False, None),
    ("occupancy/log-odds-value", "2.197", True, None),
    ("occupancy/log-odds-value", "0.954", False, "log10"),
    ("occupancy/two-readings", "[1.35, 0.794]", True, None),
    ("occupancy/readings-needed", "4", True, None),
    ("occupancy/readings-needed", "3", False, "rounded-down"),
    ("occupancy/grid-memory", "4", True, None),
    ("occupancy/grid-memory", "0.002", False, "not-squared"),
]


@pytest.mark.parametrize(("exercise_id", "answer", "passes", "misconception"), CANONICAL)
def test_canonical_answers(
    exercise_id: str, answer: str, passes: bool, misconception: str | None
) -> None:
    from slamcourse.course import variants

    spec = COURSE.exercise(exercise_id)
    verdict = get_kind(spec.kind).check(spec, variants.variant(spec, 0), answer)
    assert verdict.passed == passes, verdict.feedback
    assert verdict.misconception == misconception, verdict.feedback
