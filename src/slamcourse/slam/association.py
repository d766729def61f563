"""Data association: how far is a measurement from a prediction, in units of its uncertainty?

A measurement ``z`` (shape ``(m,)``, e.g. ``[range m, bearing rad]``) is compared with the
predicted measurement ``h`` of a candidate landmark through the innovation ``ν = z − h`` and its
covariance ``S`` (shape ``(m, m)``, symmetric positive definite, units of ``ν`` squared). The
squared Mahalanobis distance

    d² = νᵀ S⁻¹ ν

is dimensionless. If the association is right and the errors Gaussian, ``d²`` follows a χ²
distribution with ``m`` degrees of freedom; the gate accepts a candidate when ``d²`` is below
that distribution's quantile at the chosen confidence (3.84 for one degree of freedom, 5.99 for
two, at 95 %).

The χ² distribution is computed here from closed forms (no scipy): for ``k`` degrees of freedom
the CDF is the regularised lower incomplete gamma function ``P(k/2, x/2)``, which for whole and
half-whole ``k/2`` follows from ``P(1/2, t) = erf(√t)``, ``P(1, t) = 1 − e^{−t}`` and the
recurrence ``P(a + 1, t) = P(a, t) − tᵃ e^{−t} / Γ(a + 1)``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "chi2_cdf",
    "chi2_quantile",
    "chi2_tail",
    "gate_decision",
    "in_gate",
    "mahalanobis_squared",
]


def mahalanobis_squared(nu: ArrayLike, s: ArrayLike) -> float:
    """``d² = νᵀ S⁻¹ ν`` of an innovation ``ν`` (shape ``(m,)``) with covariance ``S`` (``(m, m)``).

    ``S`` is never inverted: the linear system ``S x = ν`` is solved and ``d² = νᵀ x``. A scalar
    ``ν`` with a scalar variance ``S`` gives ``ν² / S``. Dimensionless, ≥ 0.
    """
    nu_vec = np.atleast_1d(np.asarray(nu, dtype=float))
    s_mat = np.atleast_2d(np.asarray(s, dtype=float))
    if s_mat.shape != (nu_vec.size, nu_vec.size):
        raise ValueError(f"S has shape {s_mat.shape}; expected ({nu_vec.size}, {nu_vec.size})")
    x = np.linalg.solve(s_mat, nu_vec)
    return float(nu_vec @ x)


def chi2_cdf(x: float, dof: int) -> float:
    """``P(χ²_dof ≤ x)``: the fraction of correct associations whose ``d²`` is at most ``x``.

    ``dof`` ≥ 1 is the number of entries of the measurement; ``x`` ≥ 0 (a negative ``x`` gives 0).
    """
    if dof < 1:
        raise ValueError(f"dof must be at least 1, got {dof}")
    t = x / 2
    if t <= 0:  # also a positive x so small that x/2 underflows
        return 0.0
    # start from a = 1/2 (odd dof) or a = 1 (even dof), then climb a → a + 1 up to dof/2
    if dof % 2:
        a, p = 0.5, math.erf(math.sqrt(t))
    else:
        a, p = 1.0, -math.expm1(-t)
    while a < dof / 2:
        p -= math.exp(a * math.log(t) - t - math.lgamma(a + 1))
        a += 1
    return min(1.0, max(0.0, p))


def chi2_tail(x: float, dof: int) -> float:
    """``P(χ²_dof > x)``: how often a *correct* association would be at least this far away."""
    return 1.0 - chi2_cdf(x, dof)


def chi2_quantile(confidence: float, dof: int) -> float:
    """The gate threshold: the ``x`` with ``P(χ²_dof ≤ x) = confidence`` (0 < confidence < 1).

    Closed forms for one and two degrees of freedom (``z²`` with ``z`` the normal quantile at
    ``(1 + p)/2``, and ``−2 ln(1 − p)``); bisection on :func:`chi2_cdf` otherwise (to 1e-12).
    """
    if not 0 < confidence < 1:
        raise ValueError(f"confidence must lie strictly between 0 and 1, got {confidence}")
    if dof == 2:
        return -2.0 * math.log1p(-confidence)
    if dof == 1:
        from statistics import NormalDist

        return NormalDist().inv_cdf((1 + confidence) / 2) ** 2
    low, high = 0.0, float(dof)
    while chi2_cdf(high, dof) < confidence:
        high *= 2
    while high - low > 1e-12 * max(1.0, high):
        mid = (low + high) / 2
        low, high = (mid, high) if chi2_cdf(mid, dof) < confidence else (low, mid)
    return (low + high) / 2


def in_gate(d2: float, dof: int, confidence: float) -> bool:
    """Accept a candidate when ``d² < χ²_dof(confidence)``."""
    return d2 < chi2_quantile(confidence, dof)


def gate_decision(d2s: Sequence[float], dof: int, confidence: float) -> int:
    """Nearest neighbour inside the gate: the index of the smallest ``d²`` among the candidates
    that pass :func:`in_gate`, or −1 when none does (the measurement starts a new landmark)."""
    inside = [(d2, j) for j, d2 in enumerate(d2s) if in_gate(d2, dof, confidence)]
    return min(inside)[1] if inside else -1
