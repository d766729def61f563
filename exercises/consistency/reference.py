"""Reference answers for chapter ``consistency``: NEES, NIS and their χ² bands.

The mathematics lives in :mod:`slamcourse.slam.consistency` (``nees``, ``nis``,
``average_band``, ``diagnose``); χ² quantiles come from :mod:`slamcourse.slam.association`.
Functions whose name starts with ``mistake_`` compute the answer of a named misconception;
Hypothesis strategies import Hypothesis inside their body.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from slamcourse.slam import consistency
from slamcourse.slam.association import chi2_quantile

# --- NEES of one estimate ---------------------------------------------------------------------


def _p(pxx: float, pxy: float, pyy: float) -> list[list[float]]:
    return [[pxx, pxy], [pxy, pyy]]


def nees_value(
    xt: float, yt: float, xh: float, yh: float, pxx: float, pxy: float, pyy: float
) -> float:
    """NEES of a 2-D position estimate: ``eᵀ P⁻¹ e`` with ``e = x − x̂``."""
    return consistency.nees([xt, yt], [xh, yh], _p(pxx, pxy, pyy))


def mistake_nees_euclidean(
    xt: float, yt: float, xh: float, yh: float, pxx: float, pxy: float, pyy: float
) -> float:
    """``eᵀe``: the squared error in m², ``P`` ignored."""
    return (xt - xh) ** 2 + (yt - yh) ** 2


def mistake_nees_diagonal(
    xt: float, yt: float, xh: float, yh: float, pxx: float, pxy: float, pyy: float
) -> float:
    """Each squared error over its own variance: the correlation ``P_xy`` dropped."""
    return (xt - xh) ** 2 / pxx + (yt - yh) ** 2 / pyy


def mistake_nees_times_p(
    xt: float, yt: float, xh: float, yh: float, pxx: float, pxy: float, pyy: float
) -> float:
    """``eᵀ P e``: multiplied by the covariance instead of its inverse."""
    e = np.array([xt - xh, yt - yh])
    return float(e @ np.array(_p(pxx, pxy, pyy)) @ e)


# --- the band of the average NEES -------------------------------------------------------------


def anees_band(dof: int, runs: int, confidence: float) -> list[float]:
    """``[χ²_{nN}((1 − p)/2), χ²_{nN}((1 + p)/2)] / N``."""
    return list(consistency.average_band(int(dof), int(runs), confidence))


def mistake_band_not_averaged(dof: int, runs: int, confidence: float) -> list[float]:
    """The quantiles of χ²_{nN} themselves: the band of the *sum*, not of the average."""
    low, high = consistency.average_band(int(dof), int(runs), confidence)
    return [low * runs, high * runs]


def mistake_band_one_run(dof: int, runs: int, confidence: float) -> list[float]:
    """The band of a single run, χ²_n quantiles, whatever the number of runs."""
    return list(consistency.average_band(int(dof), 1, confidence))


def mistake_band_one_sided(dof: int, runs: int, confidence: float) -> list[float]:
    """Quantiles at ``1 − p`` and ``p``: each tail given the whole ``1 − p``."""
    total = int(dof) * int(runs)
    return [chi2_quantile(1 - confidence, total) / runs, chi2_quantile(confidence, total) / runs]


# --- diagnosis --------------------------------------------------------------------------------


def diagnosis(dof: int, runs: int, ratio: float, anees: float) -> str:
    """``a`` consistent, ``b`` over-confident, ``c`` pessimistic (two-sided 95 % band)."""
    verdict = consistency.diagnose(anees, int(dof), int(runs), 0.95)
    return {"consistent": "a", "over-confident": "b", "pessimistic": "c"}[verdict]


# --- code: nees -------------------------------------------------------------------------------


def nees(x_true: ArrayLike, x_hat: ArrayLike, P: ArrayLike) -> float:
    return consistency.nees(x_true, x_hat, P, angle_indices=(2,))


def nees_inputs() -> Any:
    """A true state (pose within ±20 m, heading in (−π, π], 0–2 landmarks), a covariance
    (variances 0.001–1, correlated), and an estimate whose error is 0–3 standard deviations of
    it; the estimate's heading wrapped into (−π, π], so the error may cross ±π."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        landmarks = draw(st.integers(0, 2))
        n = 3 + 2 * landmarks
        coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
        x = [draw(coord), draw(coord), draw(st.floats(-math.pi, math.pi))]
        x += [draw(coord) for _ in range(2 * landmarks)]
        rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
        low = np.tril(rng.uniform(-0.6, 0.6, (n, n)), -1) + np.diag(rng.uniform(0.3, 1.0, n))
        p = low @ low.T * draw(st.sampled_from([0.01, 0.1, 1.0]))
        e = np.linalg.cholesky(p) @ rng.uniform(-3.0, 3.0, n) / math.sqrt(n) * 1.7
        x_hat = np.array(x) - e
        x_hat[2] = math.remainder(x_hat[2], 2 * math.pi)
        return {"x_true": x, "x_hat": x_hat.tolist(), "P": p.tolist()}

    return draw()


def mistake_nees_no_wrap(x_true: ArrayLike, x_hat: ArrayLike, P: ArrayLike) -> float:
    """The heading error not wrapped: an estimate just across ±π looks 2π wrong."""
    return consistency.nees(x_true, x_hat, P)


def mistake_nees_code_diagonal(x_true: ArrayLike, x_hat: ArrayLike, P: ArrayLike) -> float:
    """Each squared error over its own variance: the correlations of ``P`` dropped."""
    e = consistency.estimation_error(x_true, x_hat, (2,))
    return float(np.sum(e * e / np.diag(np.asarray(P, dtype=float))))


def mistake_nees_per_dof(x_true: ArrayLike, x_hat: ArrayLike, P: ArrayLike) -> float:
    """NEES divided by ``n``: the normalised value whose mean is 1, not ``n``."""
    return nees(x_true, x_hat, P) / len(np.asarray(x_true))


def _positive_definite(m: ArrayLike, n: int) -> bool:
    """A symmetric positive-definite ``n × n`` matrix of finite numbers."""
    a = np.asarray(m, dtype=float)
    if a.shape != (n, n) or not np.all(np.isfinite(a)) or not np.allclose(a, a.T, atol=1e-12):
        return False
    try:
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return False
    return bool(np.linalg.cond(a) < 1e10)


def nees_valid(x_true: ArrayLike, x_hat: ArrayLike, P: ArrayLike) -> bool:
    """``nees``'s domain: two states of the same length ``3 + 2N`` (0 ≤ N ≤ 2) whose headings
    (entry 2) lie in (−π, π], and a symmetric positive-definite ``P`` of that size."""
    xt, xh = np.asarray(x_true, dtype=float), np.asarray(x_hat, dtype=float)
    if xt.ndim != 1 or xt.shape != xh.shape or xt.size not in (3, 5, 7):
        return False
    if not all(-math.pi < float(x[2]) <= math.pi for x in (xt, xh)):
        return False
    return _positive_definite(P, xt.size)
