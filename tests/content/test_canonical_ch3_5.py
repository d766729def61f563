"""The canonical (variant 0) answer of every non-code exercise of chapters 3–5, pinned.

Each expected value is derived here from the mathematics (by hand, with exact fractions, by
counting, by a plain loop), never by calling a chapter's ``reference.py`` or
``slamcourse.slam``, so a wrong reference cannot hide behind its own answer. For every exercise
the test checks that the engine's reference answer equals the independent value *and* that the
engine accepts the independent value as an answer. A second test checks that the figures the
chapters quote are the ones the mathematics gives.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any

import numpy as np
import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.locate import bundled_course_root
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind

ROOT = bundled_course_root()
COURSE = load_course(ROOT)
CHAPTERS = ("association", "drift", "graph")


def _solve_exact(a: list[list[int]], b: list[int]) -> list[Fraction]:
    """Gauss–Jordan elimination in exact fractions."""
    n = len(b)
    m = [[Fraction(x) for x in row] + [Fraction(y)] for row, y in zip(a, b, strict=True)]
    for col in range(n):
        pivot = next(r for r in range(col, n) if m[r][col] != 0)
        m[col], m[pivot] = m[pivot], m[col]
        m[col] = [x / m[col][col] for x in m[col]]
        for r in range(n):
            if r != col:
                m[r] = [x - m[r][col] * y for x, y in zip(m[r], m[col], strict=True)]
    return [m[r][n] for r in range(n)]


def _band_count(n: int, width: int) -> int:
    """Entries (i, j) of an n × n matrix with |i − j| ≤ width, counted one by one."""
    return sum(1 for i in range(n) for j in range(max(0, i - width), min(n, i + width + 1)))


# the lesson's 3-pose loop: odometry 0→1, 1→2, loop closure 0→2 (ω = 1), prior 10 on x_0
LOOP_OMEGA = [[10 + 1 + 1, -1, -1], [-1, 1 + 1, -1], [-1, -1, 1 + 1]]
LOOP_XI = [10, 1, 3]


def _chain_covariance_nonzeros(n: int) -> int:
    # x_k = x_0 + u_1 + … + u_k, all unit variance: Cov(x_i, x_j) = 1 + min(i, j)
    sigma = np.array([[1.0 + min(i, j) for j in range(n)] for i in range(n)])
    omega = np.zeros((n, n))
    for k in range(n - 1):
        omega[k : k + 2, k : k + 2] += [[1, -1], [-1, 1]]
    omega[0, 0] += 1
    assert np.allclose(sigma @ omega, np.eye(n))  # it really is Ω⁻¹
    return int(np.count_nonzero(sigma))


def _chi2_4_quantile(p: float) -> float:
    """χ² with 4 degrees of freedom: P(x) = 1 − e^{−x/2}(1 + x/2), inverted by bisection."""
    low, high = 0.0, 100.0
    for _ in range(200):
        mid = (low + high) / 2
        if 1 - math.exp(-mid / 2) * (1 + mid / 2) < p:
            low = mid
        else:
            high = mid
    return (low + high) / 2


def _ring_factor_nonzeros(n: int) -> int:
    """Nonzeros of the numeric Cholesky factor of a ring's Ω (unit edges, unit prior on x_0)."""
    omega = np.zeros((n, n))
    for i, j in [(k, k + 1) for k in range(n - 1)] + [(n - 1, 0)]:
        omega[np.ix_([i, j], [i, j])] += [[1, -1], [-1, 1]]
    omega[0, 0] += 1
    return int(np.count_nonzero(np.abs(np.linalg.cholesky(omega)) > 1e-12))


def _gate_choice() -> str:
    d2_a = 0.3**2 / 0.25 + 0.09**2 / 0.01  # 0.36 + 0.81
    d2_b = 0.15**2 / 0.25 + 0.29**2 / 0.01  # 0.09 + 8.41
    gate = -2 * math.log(1 - 0.95)
    inside = {name: d2 for name, d2 in (("a", d2_a), ("b", d2_b)) if d2 < gate}
    return min(inside, key=inside.__getitem__) if inside else "c"


CANONICAL: dict[str, Any] = {
    "graph/edge-omega": [[0, 0, 0, 0], [0, 4, 0, -4], [0, 0, 0, 0], [0, -4, 0, 4]],
    "graph/edge-xi": [0, -10, 0, 10],
    # chapter 3: association
    "association/mahalanobis-scalar": 0.5**2 / 0.25,
    "association/mahalanobis-2d": 0.36 + 0.81,
    "association/chi2-percentile": 100 * math.erf(1 / math.sqrt(2)),  # P(|z| ≤ 1)
    "association/gate-threshold": -2 * math.log(1 - 0.95),  # 1 − e^{−x/2} = 0.95
    "association/gate-decision": [_gate_choice()],
    "association/gate-tail": 100 * math.exp(-8.5 / 2),
    "association/nearest-neighbour-bug": 6,
    "association/wrong-association": ["a", "c", "d", "f"],
    "association/joint-compatibility": ["b"],
    "association/joint-gate": _chi2_4_quantile(0.95),  # 2 pairings × 2 entries
    # chapter 4: drift
    "drift/systematic-drift": 0.1 * 100,
    "drift/random-drift": math.sqrt(400 * 0.05**2),
    "drift/square-loop": abs(sum(0.02 * 100 * 1j**side for side in range(4))),
    "drift/heading-drift-value": sum(0.5 * math.sin(0.01 * k) for k in range(1, 101)),
    "drift/why-heading": ["b"],
    "drift/loop-correction": ["c"],
    "drift/correction-share": 2.0 * 4 / 10,
    # chapter 5: graph
    "graph/omega-entry": LOOP_OMEGA[0][0],
    "graph/omega-nonzeros": sum(1 for row in LOOP_OMEGA for x in row if x != 0),
    "graph/omega-matrix": LOOP_OMEGA,
    "graph/solve-first": float(_solve_exact(LOOP_OMEGA, LOOP_XI)[0]),
    "graph/solve-estimate": [float(x) for x in _solve_exact(LOOP_OMEGA, LOOP_XI)],
    "graph/chain-blocks": _band_count(1000, 1),
    "graph/chain-sparsity": 100 * _band_count(1000, 1) / 1000**2,
    "graph/loop-closure-blocks": _band_count(1000, 1) + 2 * 5,
    "graph/covariance-dense": _chain_covariance_nonzeros(5),
    "graph/variable-ordering": ["b", "d", "e"],
    "graph/loop-fill": _ring_factor_nonzeros(6),
}


def test_hand_values_are_what_the_lesson_intends() -> None:
    # a few of the values above, written out, so a slip in the derivations shows too
    assert _solve_exact(LOOP_OMEGA, LOOP_XI) == [Fraction(7, 5), Fraction(46, 15), Fraction(56, 15)]
    assert CANONICAL["graph/chain-blocks"] == 2998
    assert CANONICAL["graph/omega-nonzeros"] == 9
    assert CANONICAL["graph/loop-fill"] == 3 * 6 - 3
    assert CANONICAL["drift/heading-drift-value"] == pytest.approx(23.195, abs=5e-4)


def test_every_non_code_exercise_of_chapters_3_to_5_is_pinned() -> None:
    ids = [e for c in COURSE.chapters if c.id in CHAPTERS for e in c.exercises]
    non_code = {e for e in ids if COURSE.exercise(e).kind != "code"}
    assert non_code == set(CANONICAL)


@pytest.mark.parametrize("exercise_id", sorted(CANONICAL))
def test_canonical_answer(exercise_id: str) -> None:
    spec = COURSE.exercise(exercise_id)
    kind = get_kind(spec.kind)
    v = variant(spec, 0)
    want = CANONICAL[exercise_id]
    got = kind.expected(spec, v)
    if spec.kind in ("choice", "multi"):
        assert sorted(got) == sorted(want)
        labels = kind.labels(spec, v)  # the letters variant 0 shows them under
        answer = " ".join(labels[w] for w in want)
    elif spec.kind == "line":
        assert got == want
        answer = str(want)
    else:
        assert np.allclose(got, want, rtol=1e-9, atol=1e-12), (got, want)
        answer = repr(want)
    verdict = kind.check(spec, v, answer)
    assert verdict.passed, verdict.feedback


def _text(name: str) -> str:
    return (ROOT / "chapters" / name).read_text(encoding="utf-8")


FIGURES = [
    # (chapter file, the figure as the prose writes it)
    ("03-association.md", f"$d^2 = {0.3**2 / 0.25 + 0.09**2 / 0.01:.2f}$"),
    ("03-association.md", f"{100 * math.erf(1 / math.sqrt(2)):.1f} %"),
    ("03-association.md", f"{-2 * math.log(0.05):.2f}"),
    ("03-association.md", f"{1.959964**2:.2f}"),
    ("03-association.md", f"{-2 * math.log(0.01):.2f}"),
    ("03-association.md", f"{100 * math.exp(-3.84 / 2):.1f} %"),
    ("03-association.md", f"{_chi2_4_quantile(0.95):.2f} at 95 %"),
    ("03-association.md", f"({2 * -2 * math.log(0.05):.2f})"),
    ("04-drift.md", f"{sum(0.5 * math.sin(0.01 * k) for k in range(1, 101)):.2f} m"),
    ("04-drift.md", f"= {0.005 * sum(range(1, 101)):.2f}$ m"),
    ("04-drift.md", f"{50 * math.sin(1):.2f} m"),
    ("04-drift.md", f"{2 * math.sqrt(2):.2f}$ m"),
    ("04-drift.md", f"{50 * math.sin(math.radians(1)):.2f} m"),
    ("04-drift.md", f"{100 * (1 - math.sin(1)):.0f} %"),
    ("04-drift.md", f"pose 4 by {2.0 * 4 / 10:.1f} m"),
    ("05-graph.md", "[1.4,\\ 46/15,\\ 56/15]"),
    ("05-graph.md", f"{_band_count(1000, 1)} nonzero blocks"),
    ("05-graph.md", f"count to {_band_count(1000, 1) + 10}"),
    ("05-graph.md", f"{2 * 1000 - 1} nonzeros"),
    ("05-graph.md", f"{_ring_factor_nonzeros(1000)}\nnonzeros"),  # chain plus one closure
    ("05-graph.md", "[{:g}, {:g}, {:g}]".format(*np.array(LOOP_OMEGA) @ [1.4, 2.0, 2.6])),
]


@pytest.mark.parametrize(("chapter", "figure"), FIGURES)
def test_the_prose_quotes_the_computed_figure(chapter: str, figure: str) -> None:
    assert figure in _text(chapter)


@pytest.mark.parametrize(
    ("chapter", "placeholder"),
    [(c, "a later version expands it") for c in ("03-association.md", "04-drift.md")],
)
def test_no_placeholder_is_left(chapter: str, placeholder: str) -> None:
    assert placeholder not in _text(chapter)


def test_the_chapters_have_the_depth_of_chapters_1_and_2() -> None:
    for name in ("03-association.md", "04-drift.md", "05-graph.md"):
        assert len(_text(name).split()) >= 800, name
