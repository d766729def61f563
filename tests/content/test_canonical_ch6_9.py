"""Canonical answers of chapters 6–9 (``vision``, ``factor-graphs``, ``occupancy``, ``capstone``).

Every non-code exercise's variant 0 (the lesson's own numbers) is pinned to a value derived here
from the mathematics, by a route independent of the reference code: closed forms worked out by
hand, counting, or a different numerical method (e.g. eigenvalues of ``MᵀM`` instead of an SVD,
the normal quantile instead of the χ² one, a loop instead of a logarithm). A new non-code
exercise in these chapters fails :func:`test_every_non_code_exercise_is_pinned` until it is
pinned here.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from slamcourse.course.loader import load_course
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind

ROOT = Path(__file__).resolve().parents[2]
CHAPTERS = ("vision", "factor-graphs", "occupancy", "capstone")
COURSE = load_course(ROOT)


def logit(p: float) -> float:
    return math.log(p) - math.log1p(-p)


def count_until(start: float, step: float, done: Callable[[float], bool]) -> int:
    """How many additions of ``step`` to ``start`` until ``done`` holds (a plain loop)."""
    value, n = start, 0
    while not done(value):
        value += step
        n += 1
    return n


def ransac_by_loop(w: float, s: int, p: float) -> int:
    """Smallest N with (1 − wˢ)ᴺ ≤ 1 − p, found by counting."""
    miss, n = 1.0, 0
    while miss > 1 - p:
        miss *= 1 - w**s
        n += 1
    return n


def _singular_values_by_eigen(M: list[list[float]]) -> list[float]:
    """Singular values as square roots of the eigenvalues of MᵀM (not an SVD)."""
    A = np.asarray(M, dtype=float)
    eig = np.linalg.eigvalsh(A.T @ A)
    return sorted((math.sqrt(max(e, 0.0)) for e in eig), reverse=True)


def _fundamental_by_hand() -> list[list[float]]:
    """F = K⁻ᵀ [t]× K⁻¹ for f = 500, c = (320, 240), t = (0.8, 0, 0.6), entry by entry.

    With K⁻¹ = [[1/f, 0, −cx/f], [0, 1/f, −cy/f], [0, 0, 1]] and E = [t]×:
    F_ij = Σ_kl (K⁻¹)_ki E_kl (K⁻¹)_lj, written out for this E (E12 = −tz, E13 = ty,
    E21 = tz, E23 = −tx, E31 = −ty, E32 = tx).
    """
    f, cx, cy = 500.0, 320.0, 240.0
    tx, ty, tz = 0.8, 0.0, 0.6
    a = [[1 / f, 0.0, -cx / f], [0.0, 1 / f, -cy / f], [0.0, 0.0, 1.0]]  # K⁻¹ by hand
    E = [[0.0, -tz, ty], [tz, 0.0, -tx], [-ty, tx, 0.0]]
    return [
        [sum(a[k][i] * E[k][m] * a[m][j] for k in range(3) for m in range(3)) for j in range(3)]
        for i in range(3)
    ]


def chi2_1_quantile(p: float) -> float:
    """The p-quantile of χ² with 1 DOF by bisection on its CDF, P(Z² ≤ x) = erf(√(x/2))."""
    lo, hi = 0.0, 100.0
    for _ in range(200):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if math.erf(math.sqrt(mid / 2)) < p else (lo, mid)
    return (lo + hi) / 2


# exercise id → value derived by hand (the comment says how)
EXPECTED: dict[str, Any] = {
    "occupancy/prior-update": [math.log(108 / 7), 108 / 115],
    "vision/hartley-normalise": (lambda s: [[s, 0, -375 * s], [0, s, -205 * s], [0, 0, 1]])(
        4
        * math.sqrt(2)
        / (math.sqrt(133250) + math.sqrt(63850) + math.sqrt(80450) + math.sqrt(7650))
    ),
    # --- vision ---
    "vision/essential-dof": 3 + 3 - 1,  # rotation + translation − scale
    "vision/essential-singular-values": [2.0, 2.0, 0.0],  # |t| = |(1.6, 0, 1.2)| = 2, twice
    "vision/epipolar-value": 0.6 * -0.3 + 0.2 * 0.0 + 1 * 0.09,  # x′·(Mx), Mx = [−0.3, 0, 0.09]
    "vision/matrix-singular-values": [math.sqrt(1.25), math.sqrt(1.09), 0.0],  # √(1+a²), √(1+b²)
    "vision/essential-test": ["a"],
    "vision/five-point": 5,
    "vision/fundamental-dof": 9 - 1 - 1,
    "vision/fundamental-from-essential": _fundamental_by_hand(),
    "vision/stereo-scale": [2.5 * 0.8, 0.0, 2.5 * 0.6],
    "vision/ransac-count": ransac_by_loop(0.5, 5, 0.99),
    "vision/ransac-better-matches": ransac_by_loop(0.8, 5, 0.99),
    "vision/ransac-eight-point": ransac_by_loop(0.5, 8, 0.99),
    "vision/inlier-threshold": 1.5**2 * chi2_1_quantile(0.95),
    "vision/ransac-bug": 10,
    # --- factor-graphs ---
    "factor-graphs/factor-count": [1 + 4 + 3 * 2, 5 + 3],
    "factor-graphs/constraint-dof": 100 * 3 + 200 * 2,
    "factor-graphs/over-determined": (100 * 3 + 200 * 2) - (100 * 3 + 50 * 2),
    "factor-graphs/slam-steps": ["a", "b", "c", "d", "e"],
    "factor-graphs/chain-elimination-edge": [1, 3],  # x2's neighbours in x0–x1–x2–x3–x4
    # order x2, x3, x4, x1, x0: x2 links x1–x3, x3 then links x1–x4, the rest add nothing
    "factor-graphs/middle-out-fill": 2,
    "factor-graphs/star-fill-in": math.comb(4, 2),
    # --- occupancy ---
    "occupancy/log-odds-value": math.log(9.0),
    "occupancy/two-readings": [
        math.log(9.0) + math.log(3 / 7),
        (0.9 * 0.3) / (0.9 * 0.3 + 0.1 * 0.7),  # Bayes' rule with the odds, not log-odds
    ],
    "occupancy/back-to-even": count_until(
        math.log(9.0) + math.log(3 / 7), math.log(3 / 7), lambda v: v <= 0
    ),
    "occupancy/readings-needed": count_until(0.0, math.log(7 / 3), lambda v: v >= math.log(19)),
    "occupancy/grid-memory": 2000**2 / 1e6,
    "occupancy/grid-3d-memory": 10_000**3 / 1e12,
    "occupancy/unclamped-flip": count_until(50 * math.log(9.0), math.log(3 / 7), lambda v: v < 0),
    "occupancy/clamped-flip": count_until(5.0, math.log(3 / 7), lambda v: v < 0),
    # --- capstone ---
    "capstone/graph-variables": (5 * 60 * 10 // 10) * (1 + 2),
    "capstone/odometry-step": [0.01 * 0.5, 0.5 * 0.5 * math.pi / 180],
    "capstone/odometry-accumulated": [0.005 * 10, 0.00436 * 10],
    "capstone/lateral-drift": 50 * math.sin(2.5 * math.pi / 180),
    "capstone/scan-landmarks": [360 * 0.3, 360 * 0.3 / 20],
    "capstone/slam-memory": [
        (50 / 0.02) ** 2 / 1e6,
        ((300 * 3 + 600 * 2) + 3 * (300 * 9 + 600 * 4)) * 8 / 1e3,
    ],
    "capstone/loop-closure-checks": ["a", "b", "c", "d"],
    "capstone/frame-pipeline": ["a", "b", "c", "d", "e", "f"],
    "capstone/time-budget": [80.5, 100 - 80.5],
}


def _non_code_ids() -> list[str]:
    return [
        eid
        for eid in COURSE.exercise_ids
        if eid.split("/")[0] in CHAPTERS and COURSE.exercise(eid).kind != "code"
    ]


def test_every_non_code_exercise_is_pinned() -> None:
    assert sorted(_non_code_ids()) == sorted(EXPECTED)


@pytest.mark.parametrize("exercise_id", sorted(EXPECTED))
def test_canonical_answer(exercise_id: str) -> None:
    spec = COURSE.exercise(exercise_id)
    got = get_kind(spec.kind).expected(spec, variant(spec, 0))
    want = EXPECTED[exercise_id]
    if isinstance(want, list) and want and isinstance(want[0], str):
        assert list(got) == want
    elif isinstance(want, int):
        assert got == want
    else:
        np.testing.assert_allclose(
            np.asarray(got, dtype=float), np.asarray(want, dtype=float), rtol=1e-9, atol=1e-12
        )


def test_lesson_figures_that_the_course_corrects() -> None:
    """Seed figures that are wrong, and what the mathematics says instead."""
    # the lesson's matrix is not essential: its nonzero singular values differ
    s = _singular_values_by_eigen([[0, -1, 0], [1, 0, -0.5], [0, 0.3, 0]])
    assert s[0] == pytest.approx(1.118, abs=5e-4) and s[1] == pytest.approx(1.044, abs=5e-4)
    assert abs(s[0] - s[1]) > 0.07
    # back to 50/50 after 0.9 then 0.3: 1.35 / 0.847 ≈ 1.59 more readings, not 2.6
    assert (math.log(9) + math.log(3 / 7)) / -math.log(3 / 7) == pytest.approx(1.593, abs=1e-3)
    # log-odds of 0.95 is 2.944, not 3
    assert logit(0.95) == pytest.approx(2.944, abs=1e-3)
    # a cell seen 50 times at 0.9 needs 130 free readings at 0.3, not "50+"
    assert EXPECTED["occupancy/unclamped-flip"] == 130


def _prose(name: str) -> str:
    return " ".join((ROOT / "chapters" / name).read_text(encoding="utf-8").split())


def test_prose_figures_come_from_the_course_library() -> None:
    """The figures quoted in the chapters' prose are the library's (not typed-in seed figures)."""
    from slamcourse.slam import capstone, occupancy, vision

    ransac = [vision.ransac_iterations(w, s, 0.99) for w, s in [(0.5, 5), (0.8, 5), (0.5, 8)]]
    ch6 = _prose("06-vision.md")
    assert f"this is {ransac[0]} iterations" in ch6
    assert f"146 becomes {ransac[1]}" in ch6 and f"it becomes {ransac[2]}" in ch6
    assert f"95 % quantile is {vision.chi2_quantile(0.95, 1):.2f}" in ch6

    ch8 = _prose("08-occupancy.md")
    l_occ, l_free = occupancy.log_odds(0.9), occupancy.log_odds(0.3)
    assert f"A reading of 0.9 adds {l_occ:.3f}" in ch8 and f"adds ${l_free:.3f}$" in ch8
    assert f"$p = 0.95$ is $l = {occupancy.log_odds(0.95):.3f}$" in ch8
    assert f"outweighs ${l_occ:.3f} / {-l_free:.3f} \\approx {l_occ / -l_free:.1f}$" in ch8
    after_two = occupancy.fuse([0.9, 0.3])
    assert f"$l = {after_two:.3f}$" in ch8
    words = ["zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine"]
    assert f"that is {words[occupancy.readings_to_reach(after_two, 0.0, 0.3)]}, bring" in ch8
    flips = occupancy.readings_to_flip(occupancy.fuse([0.9] * 50), 0.3)
    assert f"survives {flips} scans" in ch8
    assert f"from $l = 5$, {words[occupancy.readings_to_flip(5, 0.3)]} free readings" in ch8
    assert f"\\approx {occupancy.probability(5):.3f}$" in ch8

    ch9 = _prose("09-capstone.md")
    assert f"At 1 cm the same office takes {capstone.grid_bytes(50, 0.01) / 1e6:.0f} MB" in ch9
    assert f"at 5 mm {capstone.grid_bytes(50, 0.005) / 1e6:.0f} MB" in ch9
    _, headroom = capstone.frame_headroom(10, [0.5, 15, 5, 10, 30, 20])
    assert round(headroom / 100, 1) == 0.2 and "A fifth of the frame to spare" in ch9
