"""Reference answers for chapter ``jcbb``: joint compatibility against greedy nearest neighbour.

The mathematics lives in :mod:`slamcourse.slam.jcbb` (``joint_d2``, ``hypothesis_d2``,
``greedy_nn``, ``jcbb``) and χ² quantiles in :mod:`slamcourse.slam.association`. Functions whose
name starts with ``mistake_`` compute the answer of a named misconception; Hypothesis strategies
import Hypothesis inside their body.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import ekfslam, jcbb
from slamcourse.slam.association import chi2_quantile

Matrix = NDArray[np.float64]


# --- two correlated innovations ---------------------------------------------------------------


def pair_d2(nu1: float, nu2: float, s1: float, s2: float, c: float) -> float:
    """Joint ``d²`` of two scalar innovations, ``νᵀ S⁻¹ ν`` with ``S = [[s1, c], [c, s2]]``."""
    return jcbb.joint_d2(np.eye(2), np.array([[s1, c], [c, s2]]), [[0.0]], [nu1, nu2])


def mistake_pair_sum_individual(nu1: float, nu2: float, s1: float, s2: float, c: float) -> float:
    """``ν₁²/s₁ + ν₂²/s₂``: each innovation on its own, the covariance ignored."""
    return nu1 * nu1 / s1 + nu2 * nu2 / s2


def mistake_pair_cross_sign(nu1: float, nu2: float, s1: float, s2: float, c: float) -> float:
    """The cross term added instead of subtracted (the inverse's off-diagonal sign lost)."""
    return (nu1 * nu1 * s2 + 2 * c * nu1 * nu2 + nu2 * nu2 * s1) / (s1 * s2 - c * c)


def mistake_pair_no_determinant(nu1: float, nu2: float, s1: float, s2: float, c: float) -> float:
    """The adjugate used as the inverse: the determinant never divided out."""
    return nu1 * nu1 * s2 - 2 * c * nu1 * nu2 + nu2 * nu2 * s1


# --- the gate of a mixed hypothesis -----------------------------------------------------------


def mixed_gate(full: int, bearing_only: int, confidence: float) -> float:
    """χ² quantile with ``2·full + bearing_only`` degrees of freedom."""
    return chi2_quantile(confidence, 2 * int(full) + int(bearing_only))


def mistake_gate_per_pairing(full: int, bearing_only: int, confidence: float) -> float:
    """One degree of freedom per pairing, whatever its size."""
    return chi2_quantile(confidence, int(full) + int(bearing_only))


def mistake_gate_all_two(full: int, bearing_only: int, confidence: float) -> float:
    """Two degrees of freedom per pairing, the bearing-only ones included."""
    return chi2_quantile(confidence, 2 * (int(full) + int(bearing_only)))


def mistake_gate_sum_of_gates(full: int, bearing_only: int, confidence: float) -> float:
    """The individual gates added up."""
    return int(full) * chi2_quantile(confidence, 2) + int(bearing_only) * chi2_quantile(
        confidence, 1
    )


# --- the two-landmark scene -------------------------------------------------------------------

# Two landmarks 1.2 m apart, 10 m ahead of a robot whose heading is uncertain (σ ≈ 0.14 rad);
# its true heading is 0.1 rad more than the estimate, so both bearings read 0.1 rad low.
SCENE_MU = (0.0, 0.0, 0.0, 10.0, 0.0, 10.0, 1.2)
SCENE_P = np.diag([0.01, 0.01, 0.02, 0.01, 0.01, 0.01, 0.01])
SCENE_R = np.diag([0.04, 0.0004])
SCENE_TRUE_POSE = (0.0, 0.0, 0.1)
HYPOTHESES = {"a": (0, 1), "b": (1, 0), "c": (0, 0), "d": (-1, 0)}  # choice id → pairing


def scene_measurements() -> list[list[float]]:
    """``z₁`` of landmark A and ``z₂`` of landmark B, seen from the true pose (noise-free)."""
    return [
        ekfslam.observe(SCENE_TRUE_POSE, SCENE_MU[3:5]).tolist(),
        ekfslam.observe(SCENE_TRUE_POSE, SCENE_MU[5:7]).tolist(),
    ]


def scene_d2(pairing: tuple[int, ...]) -> float:
    """Joint ``d²`` of a pairing of (z₁, z₂) in the scene."""
    return jcbb.hypothesis_d2(SCENE_MU, SCENE_P, scene_measurements(), SCENE_R, pairing)


def scene_choice(**_shown: float) -> str:
    """The choice JCBB makes in the scene (the prompt's d² values are shown, not used)."""
    picked = jcbb.jcbb(SCENE_MU, SCENE_P, scene_measurements(), SCENE_R, 0.95)
    return next(k for k, v in HYPOTHESES.items() if v == picked)


# --- code: joint_d2 ---------------------------------------------------------------------------


def joint_d2(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> float:
    return jcbb.joint_d2(H, P, R, nu)


def joint_inputs() -> Any:
    """A state with 2–3 landmarks and a covariance (variances 0.001–1, correlated), a hypothesis
    pairing 1–3 measurements with distinct landmarks, the stacked Jacobian, a correlated 2×2
    ``R`` and innovations of 0–3 standard deviations."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        landmarks = draw(st.integers(2, 3))
        mu = [draw(st.floats(-20, 20)), draw(st.floats(-20, 20)), draw(st.floats(-3.14, 3.14))]
        for _ in range(landmarks):
            d, a = draw(st.floats(1.0, 20.0)), draw(st.floats(-3.14, 3.14))
            mu += [mu[0] + d * math.cos(a), mu[1] + d * math.sin(a)]
        n = len(mu)
        rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
        low = np.tril(rng.uniform(-0.6, 0.6, (n, n)), -1) + np.diag(rng.uniform(0.3, 1.0, n))
        p = low @ low.T * draw(st.sampled_from([0.01, 0.1, 1.0]))
        k = draw(st.integers(1, min(3, landmarks)))
        chosen = draw(st.permutations(list(range(landmarks))))[:k]
        h = np.vstack([ekfslam.observation_jacobian(mu, j) for j in chosen])
        sr, sb = draw(st.floats(0.05, 0.5)), draw(st.floats(0.005, 0.05))
        rho = draw(st.floats(-0.8, 0.8))
        r = np.array([[sr * sr, rho * sr * sb], [rho * sr * sb, sb * sb]])
        s = h @ p @ h.T + np.kron(np.eye(k), r)
        nu = np.linalg.cholesky(s) @ rng.uniform(-3.0, 3.0, 2 * k) / math.sqrt(2 * k)
        return {"H": h.tolist(), "P": p.tolist(), "R": r.tolist(), "nu": nu.tolist()}

    return draw()


def _parts(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> tuple[Matrix, ...]:
    h, p, r = (np.asarray(a, dtype=float) for a in (H, P, R))
    return h, p, r, np.asarray(nu, dtype=float)


def mistake_joint_sum_individual(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> float:
    """The pairings' individual ``d²`` added up: the cross-covariance blocks ignored."""
    h, p, r, v = _parts(H, P, R, nu)
    total = 0.0
    for i in range(0, len(v), 2):
        hi = h[i : i + 2]
        total += float(v[i : i + 2] @ np.linalg.solve(hi @ p @ hi.T + r, v[i : i + 2]))
    return total


def mistake_joint_noise_once(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> float:
    """``R`` added to the first pairing's block only."""
    h, p, r, v = _parts(H, P, R, nu)
    s = h @ p @ h.T
    s[:2, :2] += r
    return float(v @ np.linalg.solve(s, v))


def mistake_joint_kron_order(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> float:
    """``kron(R, I)`` in place of ``kron(I, R)``: range and bearing noise interleaved wrongly."""
    h, p, r, v = _parts(H, P, R, nu)
    s = h @ p @ h.T + np.kron(r, np.eye(len(v) // 2))
    return float(v @ np.linalg.solve(s, v))


def mistake_joint_no_noise(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> float:
    """``S = H P Hᵀ``: the measurements taken as exact."""
    h, p, _, v = _parts(H, P, R, nu)
    return float(v @ np.linalg.solve(h @ p @ h.T, v))


def scene_greedy_choice(**_shown: float) -> str:
    """The choice greedy nearest neighbour makes in the scene."""
    picked = jcbb.greedy_nn(SCENE_MU, SCENE_P, scene_measurements(), SCENE_R, 0.95)
    return next(k for k, v in {**HYPOTHESES, "d": (-1, 0)}.items() if v == picked)


# --- code: joint_compatible -------------------------------------------------------------------


def joint_compatible(
    H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike, confidence: float
) -> bool:
    """``d²_H < χ²_{2k}(confidence)`` for the stacked innovation ``nu`` of ``k`` pairings."""
    nu_v = np.asarray(nu, dtype=float)
    return jcbb.joint_d2(H, P, R, nu_v) < chi2_quantile(confidence, nu_v.size)


def compatible_inputs() -> Any:
    """As :func:`joint_inputs`, with a confidence of 0.9, 0.95 or 0.99 and the innovation scaled
    so that its joint ``d²`` lies anywhere in [0, 2 × gate] but never within 5 % of the gate."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        kw = draw(joint_inputs())
        confidence = draw(st.sampled_from([0.9, 0.95, 0.99]))
        nu = np.asarray(kw["nu"], dtype=float)
        gate = chi2_quantile(confidence, nu.size)
        factor = draw(st.one_of(st.floats(0.0, 0.95), st.floats(1.05, 2.0)))
        d2 = jcbb.joint_d2(kw["H"], kw["P"], kw["R"], nu)
        if d2 <= 1e-12:
            nu = np.full(nu.size, 0.01)
            d2 = jcbb.joint_d2(kw["H"], kw["P"], kw["R"], nu)
        kw["nu"] = (nu * math.sqrt(factor * gate / d2)).tolist()
        kw["confidence"] = confidence
        return kw

    return draw()


def mistake_compatible_sum_individual(
    H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike, confidence: float
) -> bool:
    """The individual ``d²`` added up (correlations ignored), against the right gate."""
    nu_v = np.asarray(nu, dtype=float)
    return mistake_joint_sum_individual(H, P, R, nu_v) < chi2_quantile(confidence, nu_v.size)


def mistake_compatible_dof_per_pairing(
    H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike, confidence: float
) -> bool:
    """``k`` degrees of freedom (one per pairing) instead of ``2k``."""
    nu_v = np.asarray(nu, dtype=float)
    return jcbb.joint_d2(H, P, R, nu_v) < chi2_quantile(confidence, nu_v.size // 2)


def mistake_compatible_sum_of_gates(
    H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike, confidence: float
) -> bool:
    """The joint ``d²`` against ``k`` individual gates added up, ``k·χ²₂(p)``."""
    nu_v = np.asarray(nu, dtype=float)
    return jcbb.joint_d2(H, P, R, nu_v) < nu_v.size // 2 * chi2_quantile(confidence, 2)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


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


def joint_valid(H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike) -> bool:
    """``joint_d2``'s domain: ``k`` = 1–3 pairings (``H`` of shape 2k × n, ``n = 3 + 2N``),
    ``P`` and ``R`` symmetric positive definite, ``nu`` of length 2k with entries within ±10."""
    h = np.asarray(H, dtype=float)
    v = np.asarray(nu, dtype=float)
    if h.ndim != 2 or h.shape[0] not in (2, 4, 6) or h.shape[1] not in (5, 7, 9):
        return False
    if v.shape != (h.shape[0],) or not np.all(np.abs(v) <= 10):
        return False
    if not np.all(np.isfinite(h)) or not np.any(h):
        return False
    return _positive_definite(P, h.shape[1]) and _positive_definite(R, 2)


def compatible_valid(
    H: ArrayLike, P: ArrayLike, R: ArrayLike, nu: ArrayLike, confidence: float
) -> bool:
    """``joint_compatible``'s domain: as ``joint_d2``'s, a confidence of 0.9, 0.95 or 0.99, and
    ``d²`` never within 5 % of the gate."""
    if confidence not in (0.9, 0.95, 0.99) or not joint_valid(H, P, R, nu):
        return False
    v = np.asarray(nu, dtype=float)
    gate = chi2_quantile(confidence, v.size)
    return abs(jcbb.joint_d2(H, P, R, v) - gate) >= 0.049 * gate
