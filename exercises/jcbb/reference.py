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


# --- code: the JCBB search (issue 16) ---------------------------------------------------------

import itertools  # noqa: E402

from slamcourse.slam.se2 import wrap_angle  # noqa: E402


def jcbb_search(
    mu: ArrayLike, P: ArrayLike, z: ArrayLike, R: ArrayLike, confidence: float
) -> list[int]:
    """The JCBB hypothesis: ``pairing[i]`` = the landmark of measurement ``i`` or −1."""
    zs = np.asarray(z, dtype=float).reshape(-1, 2).tolist()
    return list(jcbb.jcbb(mu, P, zs, R, float(confidence)))


def _spread(draw: Any, rng: np.random.Generator, n: int) -> Matrix:
    """A covariance the way EKF-SLAM builds one: independent pose and landmark errors, each
    landmark also tied to the pose through the lever arm it was first seen with."""
    from slamcourse.grading.strategies import real

    sxy, sth = draw(real(0.05, 0.4)), draw(real(0.02, 0.15))
    d = np.empty(n)
    d[:3] = [sxy**2, sxy**2, sth**2]
    d[3:] = rng.uniform(0.05, 0.4, n - 3) ** 2
    a = np.eye(n)
    for k in range(3, n, 2):
        c = rng.uniform(0.0, 1.0)
        arm = rng.uniform(-8.0, 8.0, 2)
        a[k : k + 2, :3] = c * np.array([[1.0, 0.0, -arm[1]], [0.0, 1.0, arm[0]]])
    return np.asarray(a @ np.diag(d) @ a.T)


def jcbb_inputs() -> Any:
    """A map of 2–4 landmarks around the robot (some in clusters 0.5–2 m apart), a covariance
    built like EKF-SLAM's, a true pose off the estimate by up to 2.5 standard deviations, and
    1–4 noisy range-bearing measurements of distinct landmarks (in any order), sometimes with
    one spurious reading among them; ``R`` with range σ 0.05–0.3 m and bearing σ 0.005–0.03
    rad, possibly correlated; confidence 0.9, 0.95 or 0.99."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
        landmarks = draw(st.integers(2, 4))
        pose = [draw(real(-20, 20)), draw(real(-20, 20)), draw(real(-math.pi, math.pi))]
        mu = list(pose)
        for k in range(landmarks):
            if k > 0 and draw(st.booleans()):  # next to the previous landmark: ambiguity
                d, a = draw(real(0.5, 2.0)), draw(real(-math.pi, math.pi))
                mu += [mu[-2] + d * math.cos(a), mu[-1] + d * math.sin(a)]
            else:
                d, a = draw(real(3.0, 15.0)), draw(real(-math.pi, math.pi))
                mu += [pose[0] + d * math.cos(a), pose[1] + d * math.sin(a)]
        n = len(mu)
        p = _spread(draw, rng, n)
        sr, sb = draw(real(0.05, 0.3)), draw(real(0.005, 0.03))
        rho = draw(real(-0.5, 0.5))
        r = np.array([[sr * sr, rho * sr * sb], [rho * sr * sb, sb * sb]])
        truth = np.asarray(mu) + np.linalg.cholesky(p) @ rng.normal(size=n) * draw(real(0.0, 2.5))
        seen = draw(st.permutations(list(range(landmarks))))[: draw(st.integers(1, landmarks))]
        zs = []
        for j in seen:
            h = ekfslam.observe(truth[:3], truth[3 + 2 * j : 5 + 2 * j])
            zs.append(h + np.linalg.cholesky(r) @ rng.normal(size=2))
        if len(zs) < 4 and draw(st.booleans()):
            zs.insert(
                draw(st.integers(0, len(zs))),
                np.array([rng.uniform(1.0, 15.0), rng.uniform(-math.pi, math.pi)]),
            )
        z = [[float(v[0]), wrap_angle(float(v[1]))] for v in zs]
        confidence = draw(st.sampled_from([0.9, 0.95, 0.99]))
        return {
            "mu": [float(v) for v in mu],
            "P": p.tolist(),
            "z": z,
            "R": r.tolist(),
            "confidence": confidence,
        }

    return draw()


def jcbb_valid(mu: ArrayLike, P: ArrayLike, z: ArrayLike, R: ArrayLike, confidence: float) -> bool:
    """``jcbb_search``'s domain: 1–4 landmarks at least 0.5 m from the robot, 1–4 measurements
    (range 0.5–30 m), ``P`` and ``R`` symmetric positive definite, a confidence of 0.9, 0.95 or
    0.99; no individual or joint d² within 10⁻⁶ (relative) of its gate, JCBB's pruning finds
    the same hypothesis as a search of every hypothesis, and the best one wins by more than
    10⁻⁶ (relative) over the next with as many pairings."""
    try:
        m = np.asarray(mu, dtype=float)
        zs = np.asarray(z, dtype=float)
    except (TypeError, ValueError):
        return False
    if confidence not in (0.9, 0.95, 0.99) or m.ndim != 1 or m.size not in (5, 7, 9, 11):
        return False
    if zs.ndim != 2 or zs.shape[1] != 2 or not 1 <= zs.shape[0] <= 4:
        return False
    if not np.all(np.isfinite(zs)) or np.any(zs[:, 0] < 0.5) or np.any(zs[:, 0] > 30):
        return False
    if np.any(np.abs(zs[:, 1]) > math.pi):
        return False
    if not (_positive_definite(P, m.size) and _positive_definite(R, 2)):
        return False
    landmarks = (m.size - 3) // 2
    if any(math.dist(m[:2], m[3 + 2 * j : 5 + 2 * j]) < 0.5 for j in range(landmarks)):
        return False
    zl = zs.tolist()
    gate1 = chi2_quantile(confidence, 2)
    for i in range(len(zl)):
        for j in range(landmarks):
            pairing = [-1] * len(zl)
            pairing[i] = j
            if abs(jcbb.hypothesis_d2(m, P, zl, R, pairing) / gate1 - 1) < 1e-6:
                return False
    ranked: list[tuple[int, float]] = []
    for pairing in itertools.product(range(-1, landmarks), repeat=len(zl)):
        used = [j for j in pairing if j >= 0]
        if not used or len(used) != len(set(used)):
            continue
        d2 = jcbb.hypothesis_d2(m, P, zl, R, pairing)
        gate = jcbb.joint_gate(len(used), confidence)
        if abs(d2 / gate - 1) < 1e-6:
            return False
        if d2 < gate and all(
            jcbb.hypothesis_d2(m, P, zl, R, [j if k == i else -1 for k in range(len(zl))]) < gate1
            for i, j in enumerate(pairing)
            if j >= 0
        ):
            ranked.append((len(used), d2))
    ranked.sort(key=lambda c: (-c[0], c[1]))
    if len(ranked) >= 2 and ranked[0][0] == ranked[1][0]:
        if ranked[1][1] - ranked[0][1] <= 1e-6 * max(ranked[0][1], 1e-3):
            return False
    return jcbb.jcbb(m, P, zl, R, confidence) == jcbb.exhaustive(m, P, zl, R, confidence)


def jcbb_hypotheses(
    mu: ArrayLike, P: ArrayLike, z: ArrayLike, R: ArrayLike, confidence: float
) -> int:
    """How many hypotheses (each landmark used once) a flat list would test: for checking the
    chapter's count ``(N + 1)^m`` bounds it."""
    m = len(np.asarray(z).reshape(-1, 2))
    landmarks = (np.asarray(mu).size - 3) // 2
    return sum(
        1
        for pairing in itertools.product(range(-1, landmarks), repeat=m)
        if len([j for j in pairing if j >= 0]) == len({j for j in pairing if j >= 0})
    )
