"""Is the filter honest about its uncertainty? NEES, NIS and their χ² bands.

For an estimate ``x̂`` (n,) with covariance ``P`` (n × n) of a true state ``x`` (simulation
only: the truth is known), the **normalised estimation error squared** is

    NEES = (x − x̂)ᵀ P⁻¹ (x − x̂)

(heading entries of the error wrapped into (−π, π]). If the filter is consistent (unbiased, its
``P`` the real error covariance, errors Gaussian) NEES follows χ² with ``n`` degrees of freedom:
its mean is ``n``. The **normalised innovation squared** ``NIS = νᵀ S⁻¹ ν`` of a measurement
innovation ``ν`` (m,) with covariance ``S`` follows χ²_m, and needs no ground truth.

Averaged over ``N`` independent Monte-Carlo runs, ``N·ANEES`` follows χ²_{nN}, so the two-sided
band at confidence ``p`` for the average is ``[χ²_{nN}((1 − p)/2), χ²_{nN}((1 + p)/2)] / N``.
Above the band the filter is over-confident (``P`` too small); below it, pessimistic.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam.association import chi2_quantile, mahalanobis_squared
from slamcourse.slam.se2 import wrap_angle

Vector = NDArray[np.float64]


def estimation_error(
    x_true: ArrayLike, x_hat: ArrayLike, angle_indices: Sequence[int] = ()
) -> Vector:
    """``x − x̂`` (n,), the entries listed in ``angle_indices`` wrapped into (−π, π]."""
    e: Vector = np.asarray(x_true, dtype=float) - np.asarray(x_hat, dtype=float)
    for i in angle_indices:
        e[i] = wrap_angle(float(e[i]))
    return e


def nees(
    x_true: ArrayLike, x_hat: ArrayLike, p: ArrayLike, angle_indices: Sequence[int] = ()
) -> float:
    """``(x − x̂)ᵀ P⁻¹ (x − x̂)``: dimensionless, χ²_n for a consistent filter."""
    return mahalanobis_squared(estimation_error(x_true, x_hat, angle_indices), p)


def nis(nu: ArrayLike, s: ArrayLike) -> float:
    """``νᵀ S⁻¹ ν`` of an innovation: χ²_m for a consistent filter."""
    return mahalanobis_squared(nu, s)


def average_band(dof: int, runs: int, confidence: float = 0.95) -> tuple[float, float]:
    """Two-sided band at ``confidence`` for the average of ``runs`` independent χ²_dof values:
    ``[χ²_{dof·runs}((1 − p)/2), χ²_{dof·runs}((1 + p)/2)] / runs``."""
    total = dof * runs
    low = chi2_quantile((1 - confidence) / 2, total)
    high = chi2_quantile((1 + confidence) / 2, total)
    return low / runs, high / runs


def diagnose(average: float, dof: int, runs: int, confidence: float = 0.95) -> str:
    """``"over-confident"`` above the band, ``"pessimistic"`` below it, else ``"consistent"``."""
    low, high = average_band(dof, runs, confidence)
    if average > high:
        return "over-confident"
    if average < low:
        return "pessimistic"
    return "consistent"


def simulate_anees(
    q_filter_scale: float, runs: int = 50, steps: int = 40, seed: int = 0
) -> NDArray[np.float64]:
    """Average NEES per time step of a 1-D constant-velocity Kalman filter over ``runs`` runs.

    The truth moves with white acceleration noise (``q = 0.1`` m²/s³, ``dt = 1`` s) and a
    position sensor of variance 0.5 m²; the filter assumes ``q_filter_scale · q``. With scale 1
    it is consistent; a scale below 1 makes it over-confident. Shape (steps,), dof ``n = 2``.
    """
    rng = np.random.default_rng(seed)
    dt, q, r = 1.0, 0.1, 0.5
    f = np.array([[1.0, dt], [0.0, 1.0]])
    q_true = q * np.array([[dt**3 / 3, dt**2 / 2], [dt**2 / 2, dt]])
    q_filt = q_true * q_filter_scale
    h = np.array([[1.0, 0.0]])
    total = np.zeros(steps)
    for _ in range(runs):
        x = np.array([0.0, 1.0])
        x_hat, p = x + rng.multivariate_normal([0, 0], np.eye(2)), np.eye(2)
        for k in range(steps):
            x = f @ x + rng.multivariate_normal([0, 0], q_true)
            z = h @ x + rng.normal(0, np.sqrt(r), 1)
            x_hat, p = f @ x_hat, f @ p @ f.T + q_filt
            s = h @ p @ h.T + r
            gain = p @ h.T / s
            x_hat = x_hat + (gain @ (z - h @ x_hat)).ravel()
            p = (np.eye(2) - gain @ h) @ p
            total[k] += nees(x, x_hat, p)
    return total / runs
