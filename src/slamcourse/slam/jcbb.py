"""Joint compatibility: testing a whole data-association hypothesis at once.

A scan gives ``m`` range-bearing measurements ``z_i`` (each ``(r, φ)``, metres and radians, noise
covariance ``R``, 2×2). A **hypothesis** pairs each measurement with a mapped landmark or with
none: ``pairing[i] = j`` (0-based landmark index) or ``-1``; no landmark is used twice. For the
``k`` paired measurements the innovations ``ν_i = z_i − h_{j_i}(μ)`` are stacked into one vector
``ν_H`` (``2k``,) with covariance

    S_H = H_H P H_Hᵀ + blockdiag(R, …, R)        (2k × 2k)

where ``H_H`` stacks the measurement Jacobians (each 2 × n). The innovations share the robot
pose, so ``S_H`` has off-diagonal blocks ``H_a P H_bᵀ``. The hypothesis is **jointly compatible**
when ``d²_H = ν_Hᵀ S_H⁻¹ ν_H`` is below ``χ²_{2k}`` at the chosen confidence.

Greedy nearest neighbour decides each measurement alone (individual gates, ``χ²_2``); JCBB
(joint compatibility branch and bound) searches for the hypothesis with the most pairings that
is jointly compatible, and among those the smallest ``d²_H``.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import ekfslam
from slamcourse.slam.association import chi2_quantile

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]
Pairing = tuple[int, ...]


def joint_d2(h: ArrayLike, p: ArrayLike, r: ArrayLike, nu: ArrayLike) -> float:
    """``d² = νᵀ S⁻¹ ν`` with ``S = H P Hᵀ + blockdiag(R, …, R)``.

    ``h`` (2k × n) stacks the Jacobians of ``k`` pairings, ``p`` is the n × n state covariance,
    ``r`` the 2×2 noise of one measurement, ``nu`` (2k,) the stacked innovations. Dimensionless.
    """
    hm, pm, rm = (np.asarray(a, dtype=float) for a in (h, p, r))
    nu_v = np.asarray(nu, dtype=float).reshape(-1)
    k = hm.shape[0] // 2
    s = hm @ pm @ hm.T + np.kron(np.eye(k), rm)
    return float(nu_v @ np.linalg.solve(s, nu_v))


def stack(
    mu: ArrayLike, zs: Sequence[Sequence[float]], pairing: Sequence[int]
) -> tuple[Vector, Matrix]:
    """``(ν_H, H_H)`` of a hypothesis: stacked innovations (2k,) and Jacobians (2k × n)."""
    m = np.asarray(mu, dtype=float)
    nus, hs = [], []
    for i, j in enumerate(pairing):
        if j < 0:
            continue
        k = 3 + 2 * j
        predicted = ekfslam.observe(m[:3], m[k : k + 2])
        nus.append(ekfslam.innovation(zs[i], predicted))
        hs.append(ekfslam.observation_jacobian(m, j))
    n = m.size
    if not nus:
        return np.zeros(0), np.zeros((0, n))
    return np.concatenate(nus), np.vstack(hs)


def hypothesis_d2(
    mu: ArrayLike, p: ArrayLike, zs: Sequence[Sequence[float]], r: ArrayLike, pairing: Sequence[int]
) -> float:
    """The joint ``d²`` of a hypothesis (0 for the empty one)."""
    nu, h = stack(mu, zs, pairing)
    return 0.0 if nu.size == 0 else joint_d2(h, p, r, nu)


def joint_gate(pairings: int, confidence: float, dof_per_pairing: int = 2) -> float:
    """``χ²`` quantile for ``pairings`` stacked measurements of ``dof_per_pairing`` entries."""
    return chi2_quantile(confidence, dof_per_pairing * pairings)


def jointly_compatible(
    mu: ArrayLike,
    p: ArrayLike,
    zs: Sequence[Sequence[float]],
    r: ArrayLike,
    pairing: Sequence[int],
    confidence: float,
) -> bool:
    """``d²_H < χ²_{2k}(confidence)`` (the empty hypothesis is compatible)."""
    k = sum(1 for j in pairing if j >= 0)
    if k == 0:
        return True
    return hypothesis_d2(mu, p, zs, r, pairing) < joint_gate(k, confidence)


def _individual(
    mu: ArrayLike, p: ArrayLike, zs: Sequence[Sequence[float]], r: ArrayLike, i: int, j: int
) -> float:
    pairing = [-1] * len(zs)
    pairing[i] = j
    return hypothesis_d2(mu, p, zs, r, pairing)


def greedy_nn(
    mu: ArrayLike,
    p: ArrayLike,
    zs: Sequence[Sequence[float]],
    r: ArrayLike,
    confidence: float,
) -> Pairing:
    """Nearest neighbour, each measurement on its own: the landmark with the smallest individual
    ``d²`` inside the ``χ²_2`` gate, or −1. Two measurements may pick the same landmark."""
    landmarks = (np.asarray(mu).size - 3) // 2
    gate = chi2_quantile(confidence, 2)
    out = []
    for i in range(len(zs)):
        d2s = [(_individual(mu, p, zs, r, i, j), j) for j in range(landmarks)]
        inside = [(d2, j) for d2, j in d2s if d2 < gate]
        out.append(min(inside)[1] if inside else -1)
    return tuple(out)


def jcbb(
    mu: ArrayLike,
    p: ArrayLike,
    zs: Sequence[Sequence[float]],
    r: ArrayLike,
    confidence: float,
) -> Pairing:
    """Joint compatibility branch and bound.

    Depth first over the measurements; measurement ``i`` is tried with every unused landmark
    that is individually compatible with it and keeps the hypothesis jointly compatible, then
    left unpaired, but only if the pairings still possible can beat the best found. The best
    hypothesis has the most pairings; ties go to the smallest joint ``d²``.
    """
    landmarks = (np.asarray(mu).size - 3) // 2
    m = len(zs)
    gate1 = chi2_quantile(confidence, 2)
    individual = [
        [_individual(mu, p, zs, r, i, j) < gate1 for j in range(landmarks)] for i in range(m)
    ]
    best: list[tuple[int, float, Pairing]] = [(0, 0.0, tuple([-1] * m))]

    def search(i: int, pairing: list[int], k: int) -> None:
        if i == m:
            d2 = hypothesis_d2(mu, p, zs, r, pairing)
            if k > best[0][0] or (k == best[0][0] and d2 < best[0][1]):
                best[0] = (k, d2, tuple(pairing))
            return
        for j in range(landmarks):
            if j in pairing or not individual[i][j]:
                continue
            pairing.append(j)
            padded = pairing + [-1] * (m - i - 1)
            if jointly_compatible(mu, p, zs, r, padded, confidence):
                search(i + 1, pairing, k + 1)
            pairing.pop()
        if k + (m - i - 1) >= best[0][0]:  # the star branch can still tie or beat the best
            pairing.append(-1)
            search(i + 1, pairing, k)
            pairing.pop()

    search(0, [], 0)
    return best[0][2]


def exhaustive(
    mu: ArrayLike,
    p: ArrayLike,
    zs: Sequence[Sequence[float]],
    r: ArrayLike,
    confidence: float,
) -> Pairing:
    """The same answer as :func:`jcbb` by brute force over every hypothesis whose pairings are
    each individually compatible and which is jointly compatible as a whole."""
    landmarks = (np.asarray(mu).size - 3) // 2
    m = len(zs)
    gate1 = chi2_quantile(confidence, 2)
    best: tuple[int, float, Pairing] = (0, 0.0, tuple([-1] * m))
    for pairing in itertools.product(range(-1, landmarks), repeat=m):
        used = [j for j in pairing if j >= 0]
        if len(used) != len(set(used)):
            continue
        if any(j >= 0 and _individual(mu, p, zs, r, i, j) >= gate1 for i, j in enumerate(pairing)):
            continue
        if not jointly_compatible(mu, p, zs, r, pairing, confidence):
            continue
        d2 = hypothesis_d2(mu, p, zs, r, pairing)
        if len(used) > best[0] or (len(used) == best[0] and d2 < best[1]):
            best = (len(used), d2, pairing)
    return best[2]


def correlated_pair_d2(nu1: float, nu2: float, s1: float, s2: float, c: float) -> float:
    """``d²`` of two scalar innovations with variances ``s1``, ``s2`` and covariance ``c``."""
    det = s1 * s2 - c * c
    if det <= 0:
        raise ValueError(f"[[{s1}, {c}], [{c}, {s2}]] is not positive definite")
    return (nu1 * nu1 * s2 - 2 * c * nu1 * nu2 + nu2 * nu2 * s1) / det
