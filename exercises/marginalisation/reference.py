"""Reference answers for chapter ``marginalisation``: Schur complements, marginal covariances,
sliding windows and the fill-in marginalising creates.

Information form throughout: ``H`` (symmetric positive definite) and ``b`` with mean ``H⁻¹b``
and covariance ``H⁻¹``; marginalising the variables ``m`` out of ``(H, b)`` and keeping ``a``
gives ``H' = H_aa − H_am H_mm⁻¹ H_ma`` and ``b' = b_a − H_am H_mm⁻¹ b_m``. The mathematics lives in
:mod:`slamcourse.slam.marginal`; pose graphs (and the INTEL graph the intel chapter ships,
``exercises/intel/data/input_INTEL.g2o``, attribution in its SOURCE.md) in
:mod:`slamcourse.slam.posegraph`.

Functions whose name starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

from collections.abc import Sequence
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from slamcourse.slam import marginal as mg
from slamcourse.slam import posegraph as pg

Matrix = NDArray[np.float64]
INTEL = Path(__file__).resolve().parent.parent / "intel" / "data" / "input_INTEL.g2o"


# --- INTEL: the odometry chain before the first loop closure --------------------------------------


@lru_cache(maxsize=1)
def intel() -> pg.PoseGraph:
    return pg.parse_g2o(INTEL.read_text(encoding="utf-8"))


def first_loop_closure() -> int:
    """The first pose that closes a loop: poses 0 … (this − 1) form a pure odometry chain."""
    return min(max(e.i, e.j) for e in intel().edges if abs(e.i - e.j) != 1)


@lru_cache(maxsize=8)
def intel_chain(last: int) -> Matrix:
    """``H`` of INTEL's poses 1 … ``last`` (pose 0 held fixed: its rows and columns removed),
    linearised at the initial guess. ``last`` < :func:`first_loop_closure`: only odometry."""
    graph = intel()
    edges = [e for e in graph.edges if e.i <= last and e.j <= last]
    h, _ = pg.linear_system(graph.poses[: last + 1], edges)
    return h[3:, 3:]


def intel_marginal_sigmas(last: int) -> list[float]:
    """Marginal standard deviations (x, y, θ) of pose ``last``, pose 0 fixed."""
    block = mg.blocks([last - 1])
    return np.sqrt(np.diag(mg.marginal_covariance(intel_chain(last), block))).tolist()  # type: ignore[no-any-return]


def intel_conditional_sigmas(last: int) -> list[float]:
    """Standard deviations (x, y, θ) of pose ``last`` given every other pose: ``(H_kk)⁻¹``."""
    block = mg.blocks([last - 1])
    return np.sqrt(np.diag(mg.conditional_covariance(intel_chain(last), block))).tolist()  # type: ignore[no-any-return]


def intel_heading_sigma(last: int) -> float:
    return intel_marginal_sigmas(last)[2]


def mistake_intel_heading_conditional(last: int) -> float:
    """``1/√H_θθ`` of the last pose: its conditional, i.e. the last edge's own uncertainty."""
    return float(1 / np.sqrt(intel_chain(last)[-1, -1]))


def mistake_intel_heading_variance(last: int) -> float:
    """The variance instead of the standard deviation."""
    return intel_heading_sigma(last) ** 2


# --- numeric: the scalar example ------------------------------------------------------------------


def scalar_marginal(a: float, c: float, d: float) -> float:
    """Marginal variance of ``x₀`` for ``H = [[a, c], [c, d]]``: ``(H⁻¹)₀₀ = d / (ad − c²)``."""
    return float(mg.marginal_covariance([[a, c], [c, d]], [0])[0, 0])


def mistake_scalar_conditional(a: float, c: float, d: float) -> float:
    """``1/H₀₀``: the variance of ``x₀`` given ``x₁``."""
    return 1 / a


def mistake_scalar_inverse_of_other(a: float, c: float, d: float) -> float:
    """``(H⁻¹)₁₁ = a/(ad − c²)``: the other diagonal entry of the inverse."""
    return a / (a * d - c * c)


def mistake_scalar_plus(a: float, c: float, d: float) -> float:
    """``d/(ad + c²)``: the determinant with the wrong sign."""
    return d / (a * d + c * c)


# --- numeric: marginalising the middle of a 1-D chain ---------------------------------------------


def _chain3(p: float, w1: float, w2: float) -> Matrix:
    """``H`` of (x₀, x₁, x₂): a prior of information ``p`` on x₀, odometry ``w1``, ``w2``."""
    return np.array([[p + w1, -w1, 0.0], [-w1, w1 + w2, -w2], [0.0, -w2, w2]])


def chain_schur(p: float, w1: float, w2: float) -> list[list[float]]:
    h, _ = mg.schur_complement(_chain3(p, w1, w2), np.zeros(3), [0, 2])
    return h.tolist()  # type: ignore[no-any-return]


def mistake_chain_dropped(p: float, w1: float, w2: float) -> list[list[float]]:
    """``H_aa``: the rows and columns of x₁ dropped, as in covariance form."""
    return _chain3(p, w1, w2)[np.ix_([0, 2], [0, 2])].tolist()  # type: ignore[no-any-return]


def mistake_chain_plus(p: float, w1: float, w2: float) -> list[list[float]]:
    """``H_aa + H_am H_mm⁻¹ H_ma``: the correction added."""
    h = _chain3(p, w1, w2)
    a, m = [0, 2], [1]
    corr = h[np.ix_(a, m)] @ np.linalg.inv(h[np.ix_(m, m)]) @ h[np.ix_(m, a)]
    return (h[np.ix_(a, a)] + corr).tolist()  # type: ignore[no-any-return]


def mistake_chain_no_inverse(p: float, w1: float, w2: float) -> list[list[float]]:
    """``H_aa − H_am H_mm H_ma``: ``H_mm`` not inverted."""
    h = _chain3(p, w1, w2)
    a, m = [0, 2], [1]
    corr = h[np.ix_(a, m)] @ h[np.ix_(m, m)] @ h[np.ix_(m, a)]
    return (h[np.ix_(a, a)] - corr).tolist()  # type: ignore[no-any-return]


# --- numeric: counts ------------------------------------------------------------------------------


def _window_graph(seen: int, shared: int) -> tuple[int, list[tuple[int, int]], list[int]]:
    """Variables: pose 0, pose 1, landmarks 2 … seen+1. Pose 0 sees every landmark, pose 1 the
    first ``shared`` of them; odometry 0–1. Returns (n, edges, removed=[pose 0])."""
    n = 2 + seen
    edges = [(0, 1)] + [(0, 2 + k) for k in range(seen)] + [(1, 2 + k) for k in range(shared)]
    return n, edges, [0]


def fill_count(seen: int, shared: int) -> int:
    n, edges, removed = _window_graph(seen, shared)
    return len(mg.marginal_fill(n, edges, removed))


def mistake_fill_all_pairs(seen: int, shared: int) -> int:
    """Every pair of the Markov blanket, also those already linked."""
    k = seen + 1
    return k * (k - 1) // 2


def mistake_fill_landmarks_only(seen: int, shared: int) -> int:
    """Only the landmark pairs: the link of pose 1 to the unshared landmarks forgotten."""
    return seen * (seen - 1) // 2


def mistake_fill_ordered(seen: int, shared: int) -> int:
    """Ordered pairs: each new link counted at (i, j) and at (j, i)."""
    return 2 * fill_count(seen, shared)


def prior_size(seen: int, shared: int) -> int:
    """Scalar size of the prior left by marginalising pose 0: pose 1 (3 numbers) and the
    landmarks it saw (2 each)."""
    n, edges, removed = _window_graph(seen, shared)
    blanket = mg.markov_blanket(n, edges, removed)
    return sum(3 if v < 2 else 2 for v in blanket)


def mistake_prior_size_poses_only(seen: int, shared: int) -> int:
    """Only the pose left in the window: the landmarks forgotten."""
    return 3


def mistake_prior_size_variables(seen: int, shared: int) -> int:
    """The number of variables instead of scalars."""
    return seen + 1


def mistake_prior_size_shared(seen: int, shared: int) -> int:
    """Only pose 1 and the landmarks it shares with pose 0."""
    return 3 + 2 * shared


def ba_reduced_size(cameras: int, points: int) -> int:
    """Side of the reduced camera system after eliminating every point (6 per camera)."""
    n = cameras + points
    edges = np.column_stack(  # every point seen by every camera: (c, cameras + p)
        [np.repeat(np.arange(cameras), points), cameras + np.tile(np.arange(points), cameras)]
    )
    kept = mg.markov_blanket(n, edges, range(cameras, n))
    return 6 * len(kept)


def mistake_ba_full(cameras: int, points: int) -> int:
    return 6 * cameras + 3 * points


def mistake_ba_points(cameras: int, points: int) -> int:
    """The points' system: the cameras eliminated instead."""
    return 3 * points


# --- code: shared input generator -----------------------------------------------------------------


def _pose_graph_system(seed: int, poses: int, loops: int) -> tuple[Matrix, Matrix]:
    """``H`` and ``b`` of a small synthetic pose graph (``posegraph.simulate``: odometry and loop
    closures, σ about 5 cm and 0.02 rad) linearised at its dead-reckoning guess, with a prior of
    σ 0.1 m, 0.1 m, 0.05 rad on pose 0 (the gauge)."""
    x, edges = pg.simulate(seed, poses, loops if poses > 2 else 0)
    h, b = pg.linear_system(x, edges)
    h[:3, :3] += np.diag([100.0, 100.0, 400.0])
    return (h + h.T) / 2, b


def _realistic(m: Matrix) -> list[Any]:
    """Entries with 12 significant digits, and those below a billionth of the largest as 0
    (the grader's rule for drawn floats: rounding noise of an exactly zero error), as lists."""
    arr = np.asarray(m, dtype=float)
    scale = float(np.abs(arr).max()) if arr.size else 0.0
    arr = np.where(np.abs(arr) < 1e-9 * scale, 0.0, arr)
    return np.vectorize(lambda v: float(f"{v:.12g}") + 0.0)(arr).tolist()  # type: ignore[no-any-return]


def _system() -> Any:
    """(H, b) of a pose graph of 1–4 poses (3–12 scalars) with 0–2 loop closures."""
    from hypothesis import strategies as st

    def build(seed: int, poses: int, loops: int) -> tuple[list[Any], list[Any]]:
        h, b = _pose_graph_system(seed, poses, loops)
        hr = np.array(_realistic(h))
        return _realistic((hr + hr.T) / 2), _realistic(b)

    return st.builds(build, st.integers(0, 2**32 - 1), st.integers(1, 4), st.integers(0, 2))


def _subset(n: int, low: int, high: int, whole_poses: bool) -> Any:
    """Distinct indices into ``0 … n−1``, ``low`` to ``high`` of them, in a random order; with
    ``whole_poses`` the three indices of whole poses (when that fits the sizes)."""
    from hypothesis import strategies as st

    if whole_poses and n >= 6:
        poses = n // 3
        hi = min(poses, high // 3)
        lo = max(1, -(-low // 3))
        if lo <= hi:
            return st.permutations(list(range(poses))).flatmap(
                lambda perm: st.integers(lo, hi).map(lambda k: mg.blocks(perm[:k]))
            )
    return st.permutations(list(range(n))).flatmap(
        lambda perm: st.integers(low, high).map(lambda k: list(perm[:k]))
    )


# --- code: marginalise ----------------------------------------------------------------------------


def marginalise_inputs() -> Any:
    """``H`` and ``b`` of small pose graphs; ``keep``: 1 … n−1 indices (often whole poses) in a
    random order."""
    from hypothesis import strategies as st

    return st.tuples(_system(), st.booleans()).flatmap(
        lambda s: st.fixed_dictionaries(
            {
                "H": st.just(s[0][0]),
                "b": st.just(s[0][1]),
                "keep": _subset(len(s[0][1]), 1, len(s[0][1]) - 1, s[1]),
            }
        )
    )


def marginalise(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """``[H' | b']``: the k×(k+1) augmented system left after marginalising all but ``keep``."""
    h, g = mg.schur_complement(H, b, list(keep))
    return np.column_stack([h, g])


def _parts(H: Any, b: Any, keep: Sequence[int]) -> tuple[Matrix, Matrix, Matrix, Matrix, Matrix]:
    h = np.array(H, dtype=float)
    g = np.array(b, dtype=float)
    a = [int(k) for k in keep]
    m = [i for i in range(len(h)) if i not in a]
    return h[np.ix_(a, a)], h[np.ix_(a, m)], h[np.ix_(m, m)], g[a], g[m]


def mistake_marg_dropped(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """``[H_aa | b_a]``: the other variables' rows and columns dropped (covariance-form habit)."""
    h_aa, _, _, b_a, _ = _parts(H, b, keep)
    return np.column_stack([h_aa, b_a])


def mistake_marg_plus(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """The corrections added instead of subtracted."""
    h_aa, h_am, h_mm, b_a, b_m = _parts(H, b, keep)
    s = h_am @ np.linalg.inv(h_mm)
    return np.column_stack([h_aa + s @ h_am.T, b_a + s @ b_m])


def mistake_marg_b_unchanged(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """``H'`` right, ``b' = b_a``: the information vector not updated."""
    h_aa, h_am, h_mm, b_a, _ = _parts(H, b, keep)
    return np.column_stack([h_aa - h_am @ np.linalg.solve(h_mm, h_am.T), b_a])


def mistake_marg_no_inverse(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """``H_mm`` used where ``H_mm⁻¹`` belongs."""
    h_aa, h_am, h_mm, b_a, b_m = _parts(H, b, keep)
    return np.column_stack([h_aa - h_am @ h_mm @ h_am.T, b_a - h_am @ h_mm @ b_m])


def mistake_marg_sorted(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """Rows and columns in increasing index order, not in ``keep``'s order."""
    return marginalise(H, b, sorted(int(k) for k in keep))


def mistake_marg_first_k(H: Any, b: Any, keep: Sequence[int]) -> Matrix:
    """The first ``len(keep)`` variables kept, whatever ``keep`` says."""
    return marginalise(H, b, list(range(len(keep))))


# --- code: marginal_covariance --------------------------------------------------------------------


def covariance_inputs() -> Any:
    """``H`` of small pose graphs; ``block``: 1 … n indices (often whole poses), random order."""
    from hypothesis import strategies as st

    return st.tuples(_system(), st.booleans()).flatmap(
        lambda s: st.fixed_dictionaries(
            {
                "H": st.just(s[0][0]),
                "block": _subset(len(s[0][1]), 1, len(s[0][1]), s[1]),
            }
        )
    )


def marginal_covariance(H: Any, block: Sequence[int]) -> Matrix:
    return mg.marginal_covariance(H, list(block))


def mistake_cov_conditional(H: Any, block: Sequence[int]) -> Matrix:
    """``(H_aa)⁻¹``: the covariance of the block given all the other variables."""
    return mg.conditional_covariance(H, list(block))


def mistake_cov_information_block(H: Any, block: Sequence[int]) -> Matrix:
    """``H_aa``: the block of the information matrix, as if it were a covariance."""
    a = [int(k) for k in block]
    return np.array(H, dtype=float)[np.ix_(a, a)]


def mistake_cov_schur_not_inverted(H: Any, block: Sequence[int]) -> Matrix:
    """The marginal *information* ``H_aa − H_am H_mm⁻¹ H_ma``, not inverted."""
    h, _ = mg.schur_complement(H, np.zeros(len(H)), list(block))
    return h


def mistake_cov_sorted(H: Any, block: Sequence[int]) -> Matrix:
    """Rows and columns in increasing index order, not in ``block``'s order."""
    return marginal_covariance(H, sorted(int(k) for k in block))


def mistake_cov_variances_only(H: Any, block: Sequence[int]) -> Matrix:
    """Only the marginal variances: the cross-covariances of the block left at zero."""
    return np.diag(np.diag(marginal_covariance(H, block)))


# --- the domains the prompts state (``valid:``) ---------------------------------------------------


def _spd(H: Any) -> bool:
    try:
        h = np.array(H, dtype=float)
    except (TypeError, ValueError):
        return False
    if h.ndim != 2 or h.shape[0] != h.shape[1] or not 1 <= len(h) <= 15:
        return False
    if not np.all(np.isfinite(h)) or not np.allclose(h, h.T, rtol=0, atol=1e-9 * np.abs(h).max()):
        return False
    return bool(np.linalg.eigvalsh((h + h.T) / 2).min() > 1e-9 * np.abs(h).max())


def _distinct(idx: Sequence[int], n: int) -> bool:
    values = [int(k) for k in idx]
    return len(set(values)) == len(values) and all(0 <= k < n for k in values)


def marginalise_valid(H: Any, b: Any, keep: Sequence[int]) -> bool:
    """``H`` symmetric positive definite (n ≤ 15), ``b`` of length n, ``keep`` 1 … n−1 distinct
    indices."""
    if not _spd(H) or len(b) != len(H):
        return False
    return 1 <= len(keep) <= len(H) - 1 and _distinct(keep, len(H))


def covariance_valid(H: Any, block: Sequence[int]) -> bool:
    """``H`` symmetric positive definite (n ≤ 15), ``block`` 1 … n distinct indices."""
    return _spd(H) and 1 <= len(block) <= len(H) and _distinct(block, len(H))
