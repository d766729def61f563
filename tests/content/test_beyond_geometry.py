"""Chapters 17–18 (``orderings``, ``scan-matching``): canonical answers, figures, and how many
mutants and variants each code exercise ships.

Every non-code exercise's variant 0 is pinned to a value derived here by another route than the
reference code: fill counts from the nonzeros of a *numerical* Cholesky factor (numpy) or of
SciPy's sparse LU, closed forms worked out by hand. That every code exercise's mutants are
graded ``failed`` (not merely timed out) and its correct variants pass in the real sandbox is
checked once, by ``test_bundled_course.py::test_exercise_is_sound`` (both chapters are in its
``MUTANTS_FAIL_NOT_TIME_OUT``).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.sparse.csgraph import reverse_cuthill_mckee

from slamcourse.course.loader import load_course
from slamcourse.course.variants import variant
from slamcourse.kinds import get_kind
from slamcourse.slam import orderings as so

ROOT = Path(__file__).resolve().parents[2]
COURSE = load_course(ROOT)
CHAPTERS = ("orderings", "scan-matching")
INTEL = ROOT / "exercises" / "intel" / "data" / "input_INTEL.g2o"


def _spd(n: int, edges: list[tuple[int, int]]) -> np.ndarray:
    """A symmetric positive-definite matrix with the pattern of the graph (Laplacian + I).

    It is an M-matrix, so Cholesky never cancels: every structural nonzero of ``L`` is a true
    nonzero (fill entries decay along long chains, so compare with 0, not with a threshold).
    """
    h = np.eye(n)
    for i, j in edges:
        h[i, j] = h[j, i] = -1.0
        h[i, i] += 1.0
        h[j, j] += 1.0
    return h


def numeric_fill(n: int, edges: list[tuple[int, int]], order: list[int]) -> int:
    """Fill edges counted as the nonzeros of a numerical Cholesky factor ``L`` of ``P H Pᵀ``."""
    h = _spd(n, edges)[np.ix_(order, order)]
    lower = np.linalg.cholesky(h)
    below = int(np.count_nonzero(np.tril(lower, -1) != 0))
    original = len({(min(i, j), max(i, j)) for i, j in edges})
    return below - original


def chain_loop(n: int, a: int, b: int) -> list[tuple[int, int]]:
    return [(i, i + 1) for i in range(n - 1)] + [(a, b)]


def _intel_lines() -> list[list[str]]:
    return [line.split() for line in INTEL.read_text(encoding="utf-8").splitlines()]


def _intel_poses() -> int:
    return sum(1 for f in _intel_lines() if f and f[0] == "VERTEX_SE2")


def _intel_pairs() -> list[tuple[int, int]]:
    return sorted(
        {
            (min(int(f[1]), int(f[2])), max(int(f[1]), int(f[2])))
            for f in _intel_lines()
            if f and f[0] == "EDGE_SE2"
        }
    )


def intel_by_superlu() -> dict[str, int]:
    """Poses, distinct edges and nnz(L) of SuperLU's factors of an SPD matrix of INTEL's pattern."""
    n, pairs = _intel_poses(), _intel_pairs()
    h = sp.csc_matrix(_spd(n, pairs))
    out = {"poses": n, "edges": len(pairs)}
    for name, spec in (("natural", "NATURAL"), ("md", "MMD_AT_PLUS_A"), ("colamd", "COLAMD")):
        lu = spla.splu(h, permc_spec=spec, diag_pivot_thresh=0.0, options={"SymmetricMode": True})
        out[f"nnz_{name}"] = int(lu.L.nnz)
    return out


FIGURES = intel_by_superlu()

EXPECTED: dict[str, object] = {
    # hub first: every unordered pair of the 6 leaves, C(6, 2)
    "orderings/landmarks-first": numeric_fill(
        45,
        [(k, k + 1) for k in range(4)] + [(p, 5 + j) for j in range(40) for p in range(5)],
        list(range(5, 45)) + list(range(5)),
    ),
    "orderings/chain-loop-natural": numeric_fill(10, chain_loop(10, 2, 7), list(range(10))),
    "orderings/chain-loop-first": numeric_fill(
        10, chain_loop(10, 1, 7), [7, 0, 1, 2, 3, 4, 5, 6, 8, 9]
    ),
    "orderings/intel-nonzeros": FIGURES["nnz_md"],
    "orderings/intel-ratio": FIGURES["nnz_natural"] / FIGURES["nnz_md"],
    "orderings/why-order": ["a"],
    # the canonical motion was drawn with θ = π/6: the two points must give it back
    "scan-matching/two-point-angle": math.pi / 6,
    # (2, 3) → (14, 7): 12 steps along x, plus the start cell
    "scan-matching/beam-cells": 12 + 1,
    # 5 hits of 0.85 and 2 passes of −0.4, by hand
    "scan-matching/hit-log-odds": 3.45,
}


def _non_code_ids() -> list[str]:
    return [
        eid
        for eid in COURSE.exercise_ids
        if eid.split("/")[0] in CHAPTERS and COURSE.exercise(eid).kind != "code"
    ]


def test_hand_counts_agree_with_numeric_factors() -> None:
    assert EXPECTED["orderings/landmarks-first"] == math.comb(5, 2) - 4
    assert EXPECTED["orderings/chain-loop-natural"] == 7 - 2 - 2
    assert EXPECTED["orderings/chain-loop-first"] == 2 * (7 - 1) - 2


def test_intel_prompt_figures_are_measured() -> None:
    """The numbers the INTEL prompts give the learner, against SuperLU's factors."""
    params = variant(COURSE.exercise("orderings/intel-ratio"), 0).params
    assert params["poses"] == FIGURES["poses"] == 1228
    assert params["edges"] == FIGURES["edges"]
    assert params["fill_natural"] == FIGURES["nnz_natural"] - FIGURES["poses"] - FIGURES["edges"]
    assert params["fill_md"] == FIGURES["nnz_md"] - FIGURES["poses"] - FIGURES["edges"]
    other = variant(COURSE.exercise("orderings/intel-nonzeros"), 0).params
    assert {k: other[k] for k in ("poses", "edges", "fill_md")} == {
        k: params[k] for k in ("poses", "edges", "fill_md")
    }


def test_chapter_figures_are_measured() -> None:
    """The factor sizes the orderings chapter quotes: SuperLU's, and the symbolic count for RCM."""
    text = (ROOT / "chapters" / "16-orderings.md").read_text(encoding="utf-8")
    n, pairs = FIGURES["poses"], _intel_pairs()
    rows = [i for i, _ in pairs] + [j for _, j in pairs]
    cols = [j for _, j in pairs] + [i for i, _ in pairs]
    pattern = sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    rcm = [int(v) for v in reverse_cuthill_mckee(pattern, symmetric_mode=True)]
    for figure in (
        FIGURES["nnz_natural"],
        FIGURES["nnz_md"],
        FIGURES["nnz_colamd"],
        so.factor_nonzeros(n, pairs, rcm),
    ):
        assert f"{figure:,}" in text, figure
    assert f"{FIGURES['nnz_natural'] - n - len(pairs):,} fill edges" in text


def test_factorisation_costs_are_measured() -> None:
    """Σ c_k² of the why-order prompt, from the columns of numerical Cholesky factors (numpy)."""
    n, pairs = FIGURES["poses"], _intel_pairs()
    h = _spd(n, pairs)
    params = variant(COURSE.exercise("orderings/why-order"), 0).params
    for key, order in (
        ("cost_natural", list(range(n))),
        ("cost_md", so.min_degree_order(n, pairs)),
    ):
        lower = np.linalg.cholesky(h[np.ix_(order, order)])
        counts = np.count_nonzero(np.tril(lower, -1) != 0, axis=0)
        assert params[key] == int(np.sum(counts**2)), key


def test_every_non_code_exercise_is_pinned() -> None:
    assert sorted(_non_code_ids()) == sorted(EXPECTED)


@pytest.mark.parametrize("exercise_id", sorted(EXPECTED))
def test_canonical_answer(exercise_id: str) -> None:
    spec = COURSE.exercise(exercise_id)
    got = get_kind(spec.kind).expected(spec, variant(spec, 0))
    want = EXPECTED[exercise_id]
    if isinstance(want, list):  # choice ids
        assert list(got) == want
    elif isinstance(want, int):
        assert got == want
    else:
        np.testing.assert_allclose(
            np.asarray(got, dtype=float), np.asarray(want, dtype=float), rtol=1e-9, atol=1e-12
        )


# --- enough mutants and variants -----------------------------------------------------------------


def test_every_code_exercise_has_mutants_and_variants() -> None:
    checked = 0
    for eid in COURSE.exercise_ids:
        chapter, slug = eid.split("/")
        if chapter not in CHAPTERS or COURSE.exercise(eid).kind != "code":
            continue
        checked += 1
        folder = ROOT / "exercises" / chapter
        assert len(list((folder / "mutants" / slug).glob("*.py"))) >= 8, eid
        assert len(list((folder / "variants" / slug).glob("*.py"))) >= 3, eid
    assert checked >= 2
