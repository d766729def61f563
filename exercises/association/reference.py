"""Reference answers for chapter ``association``: which landmark produced a measurement?

A measurement ``z`` is compared with the predicted measurement ``h_j`` of each candidate landmark
through the innovation ``ν = z − h_j`` and its covariance ``S`` (here diagonal,
``S = diag(s00, s11)``: range variance in m², bearing variance in rad²). The squared Mahalanobis
distance

    d² = νᵀ S⁻¹ ν = ν₀²/s00 + ν₁²/s11

is dimensionless. For a correct association it follows a χ² distribution with as many degrees of
freedom as the measurement has entries, which gives the gate: accept when ``d²`` is below the χ²
quantile at the chosen confidence.

Every function takes the exercise's parameters as keyword arguments. Functions that return a
Hypothesis strategy import Hypothesis inside their body, and scipy is imported inside the
functions that need it: other exercises load this module and must stay fast. Functions whose
name starts with ``mistake_`` (numeric exercises) or that end in a misconception's name (code
exercises) compute a named wrong answer.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

Vector = Sequence[float]


# --- Mahalanobis distance ------------------------------------------------------------------


def mahalanobis(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """Squared Mahalanobis distance ``ν₀²/s00 + ν₁²/s11`` of a 2D innovation, diagonal ``S``."""
    return nu0 * nu0 / s00 + nu1 * nu1 / s11


def mahalanobis_scalar(nu: float, s: float) -> float:
    """Squared Mahalanobis distance ``ν²/S`` of a scalar innovation (dimensionless)."""
    return nu * nu / s


def mahalanobis_euclidean(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """Wrong: ``ν·ν``, the squared Euclidean length (S ignored)."""
    return nu0 * nu0 + nu1 * nu1


def mahalanobis_times_s(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """Wrong: ``νᵀ S ν``, multiplied by the covariance instead of divided."""
    return nu0 * nu0 * s00 + nu1 * nu1 * s11


def mahalanobis_square_root(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """Wrong: ``d`` where ``d²`` was asked for."""
    return math.sqrt(mahalanobis(nu0, nu1, s00, s11))


def mistake_scalar_euclidean(nu: float, s: float) -> float:
    """``ν²``: the squared innovation, not divided by its variance."""
    return nu * nu


def mistake_scalar_not_squared(nu: float, s: float) -> float:
    """``ν/S``: the innovation divided by the variance, not squared."""
    return nu / s


def mistake_scalar_over_sigma(nu: float, s: float) -> float:
    """``ν/σ``: the distance ``d`` itself (in standard deviations), not its square."""
    return abs(nu) / math.sqrt(s)


def mistake_2d_euclidean(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """``ν₀² + ν₁²``: the Euclidean length squared, S ignored."""
    return mahalanobis_euclidean(nu0, nu1, s00, s11)


def mistake_2d_times_s(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """``ν₀²·s00 + ν₁²·s11``: multiplied by S instead of by its inverse."""
    return mahalanobis_times_s(nu0, nu1, s00, s11)


def mistake_2d_range_only(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """``ν₀²/s00``: the bearing term left out."""
    return nu0 * nu0 / s00


# --- the χ² gate ----------------------------------------------------------------------------


def chi2_threshold(dof: int, confidence: float) -> float:
    """The χ² quantile with ``dof`` degrees of freedom at probability ``confidence``."""
    from scipy.stats import chi2  # imported here: loading this module must stay fast

    return float(chi2.ppf(confidence, dof))


def in_gate(d2: float, dof: int, confidence: float) -> bool:
    """Accept the association when ``d² < χ²_dof(confidence)``."""
    return d2 < chi2_threshold(dof, confidence)


def in_gate_one_dof(d2: float, dof: int, confidence: float) -> bool:
    """Wrong: the 1-DOF threshold whatever the measurement's size (3.84 at 95 %)."""
    return d2 < chi2_threshold(1, confidence)


def in_gate_on_distance(d2: float, dof: int, confidence: float) -> bool:
    """Wrong: ``d = √d²`` compared with a threshold meant for ``d²``."""
    return math.sqrt(d2) < chi2_threshold(dof, confidence)


def gate_inputs() -> Any:
    """Hypothesis strategy for ``in_gate``: ``d²`` at least 5 % away from the threshold, so
    rounding in a learner's own quantile cannot flip the verdict."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        dof = draw(st.sampled_from([1, 2]))
        confidence = draw(st.floats(0.5, 0.9999))
        factor = draw(st.one_of(st.floats(0.02, 0.95), st.floats(1.05, 4.0)))
        return {
            "d2": chi2_threshold(dof, confidence) * factor,
            "dof": dof,
            "confidence": confidence,
        }

    return draw()


# --- nearest neighbour ----------------------------------------------------------------------


def _d2(z: Vector, h: Vector, s00: float, s11: float) -> float:
    return mahalanobis(z[0] - h[0], z[1] - h[1], s00, s11)


def nearest_neighbour(
    z: Vector, landmarks: Sequence[Vector], s00: float, s11: float, gate: float
) -> int:
    """Index of the candidate with the smallest ``d²`` among those with ``d² < gate``; −1 if
    no candidate passes the gate (the measurement then starts a new landmark)."""
    best, best_d2 = -1, math.inf
    for j, h in enumerate(landmarks):
        d2 = _d2(z, h, s00, s11)
        if d2 < gate and d2 < best_d2:
            best, best_d2 = j, d2
    return best


def nearest_neighbour_euclidean(
    z: Vector, landmarks: Sequence[Vector], s00: float, s11: float, gate: float
) -> int:
    """Wrong (the listing's bug): the Euclidean ``ν·ν`` used as the distance and gated."""
    best, best_d2 = -1, math.inf
    for j, h in enumerate(landmarks):
        d2 = (z[0] - h[0]) ** 2 + (z[1] - h[1]) ** 2
        if d2 < gate and d2 < best_d2:
            best, best_d2 = j, d2
    return best


def nearest_neighbour_no_gate(
    z: Vector, landmarks: Sequence[Vector], s00: float, s11: float, gate: float
) -> int:
    """Wrong: the Mahalanobis-nearest candidate, even when it is outside the gate."""
    if len(landmarks) == 0:
        return -1
    return min(range(len(landmarks)), key=lambda j: _d2(z, landmarks[j], s00, s11))


def nearest_neighbour_first_in_gate(
    z: Vector, landmarks: Sequence[Vector], s00: float, s11: float, gate: float
) -> int:
    """Wrong: the first candidate inside the gate, not the best one."""
    for j, h in enumerate(landmarks):
        if _d2(z, h, s00, s11) < gate:
            return j
    return -1


def nearest_neighbour_inputs() -> Any:
    """Hypothesis strategy for ``nearest_neighbour``.

    Candidates are drawn through their whitened innovation ``u`` (``ν = u·σ``), so every ``d²``
    lies in [0, 32]. Predicted ranges stay within [0.5, 50] m (the measured range is drawn in
    [4.5, 46] m; a candidate's range is clipped to that interval) and bearings
    within ±1.4 rad, so no range is negative and no innovation ever needs wrapping.
    ``S`` is strongly anisotropic (range σ of 0.2–1 m, or in a third of the draws 1–10 m, as
    the prompt allows any positive variance; bearing σ of 0.01–0.1 rad), which is what makes
    the Euclidean distance pick the wrong candidate. Draws with a near tie between the two best
    candidates inside the gate, or a ``d²`` within 5 % of the gate, are rejected.
    """
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        s00 = draw(st.one_of(st.floats(0.04, 1.0), st.floats(0.04, 1.0), st.floats(1.0, 100.0)))
        s11 = draw(st.floats(1e-4, 0.01))
        gate = draw(st.sampled_from([4.61, 5.99, 9.21]))  # χ²₂ at 90 %, 95 %, 99 %
        z = [draw(st.floats(4.5, 46.0)), draw(st.floats(-1.0, 1.0))]
        count = draw(st.integers(0, 6))
        landmarks = []
        sigma = math.sqrt(s00)
        for _ in range(count):
            u0 = draw(st.floats(-4.0, 4.0))
            u1 = draw(st.floats(-4.0, 4.0))
            predicted = min(max(z[0] - u0 * sigma, 0.5), 50.0)
            landmarks.append([predicted, z[1] - u1 * math.sqrt(s11)])
        return {"z": z, "landmarks": landmarks, "s00": s00, "s11": s11, "gate": gate}

    return draw().filter(_unambiguous)


def _unambiguous(kw: dict[str, Any]) -> bool:
    d2s = [_d2(kw["z"], h, kw["s00"], kw["s11"]) for h in kw["landmarks"]]
    gate = kw["gate"]
    if any(abs(d - gate) < 0.05 * gate for d in d2s):
        return False
    inside = sorted(d for d in d2s if d < gate)
    return len(inside) < 2 or inside[1] - inside[0] > 0.05 * gate


# --- the gate in numbers (computed by slamcourse.slam.association) --------------------------
#
# The functions below call the course's reference library, which computes the χ² distribution
# from closed forms; the numbers are the same as scipy's (tests/unit/test_slam_ch3_5.py).


def gate_threshold(dof: int, confidence: float) -> float:
    """The χ² quantile ``χ²_dof(confidence)``: the largest ``d²`` the gate accepts."""
    from slamcourse.slam.association import chi2_quantile

    return chi2_quantile(confidence, int(dof))


def mistake_threshold_for_distance(dof: int, confidence: float) -> float:
    """``√χ²``: a threshold on ``d`` where one on ``d²`` was asked for."""
    return math.sqrt(gate_threshold(dof, confidence))


def mistake_threshold_other_dof(dof: int, confidence: float) -> float:
    """The quantile for the other number of degrees of freedom (1 ↔ 2)."""
    return gate_threshold(3 - int(dof), confidence)


def mistake_threshold_lower_tail(dof: int, confidence: float) -> float:
    """The quantile at ``1 − confidence``: the gate's complement."""
    return gate_threshold(dof, 1 - confidence)


def percent_below(d2: float, dof: int) -> float:
    """``100·P(χ²_dof ≤ d²)``: the percentage of correct associations at most this far away."""
    from slamcourse.slam.association import chi2_cdf

    return 100.0 * chi2_cdf(d2, int(dof))


def mistake_percent_above(d2: float, dof: int) -> float:
    """The tail ``100·P(χ²_dof > d²)`` where the fraction below was asked for."""
    return 100.0 - percent_below(d2, dof)


def mistake_percent_other_dof(d2: float, dof: int) -> float:
    """The CDF for the other number of degrees of freedom (1 ↔ 2)."""
    return percent_below(d2, 3 - int(dof))


def percent_as_far(d2: float, dof: int) -> float:
    """``100·P(χ²_dof ≥ d²)``: how often a *correct* association lands this far away or further."""
    from slamcourse.slam.association import chi2_tail

    return 100.0 * chi2_tail(d2, int(dof))


def mistake_tail_complement(d2: float, dof: int) -> float:
    """``100·P(χ² < d²)``: the complement of the tail."""
    return 100.0 - percent_as_far(d2, dof)


def mistake_tail_one_dof(d2: float, dof: int) -> float:
    """The tail of χ² with one degree of freedom, whatever the measurement's size."""
    return percent_as_far(d2, 1)


def mistake_tail_no_half(d2: float, dof: int) -> float:
    """``100·e^{−d²}``: the two-DOF tail ``e^{−d²/2}`` with the ½ forgotten."""
    return 100.0 * math.exp(-d2)


def gate_choice(
    nua0: float,
    nua1: float,
    nub0: float,
    nub1: float,
    s00: float,
    s11: float,
    confidence: float,
    **_derived: float,
) -> str:
    """Which choice is right: ``a`` (associate with A), ``b`` (with B) or ``c`` (new landmark).

    Each candidate's ``d²`` is its innovation's squared Mahalanobis distance with
    ``S = diag(s00, s11)``; the gate is χ²₂ at ``confidence``; nearest neighbour inside the gate.
    """
    from slamcourse.slam.association import gate_decision, mahalanobis_squared

    s = [[s00, 0.0], [0.0, s11]]
    d2s = [mahalanobis_squared([nua0, nua1], s), mahalanobis_squared([nub0, nub1], s)]
    return "abc"[gate_decision(d2s, 2, confidence)]  # index −1 picks "c"


def mahalanobis_full(nu0: float, nu1: float, s00: float, s11: float) -> float:
    """``νᵀ S⁻¹ ν`` computed as for any covariance (a linear solve), here ``S = diag(s00, s11)``."""
    from slamcourse.slam.association import mahalanobis_squared

    return mahalanobis_squared([nu0, nu1], [[s00, 0.0], [0.0, s11]])


def mahalanobis_scalar_full(nu: float, s: float) -> float:
    """``ν S⁻¹ ν`` of a one-entry innovation, by the general formula."""
    from slamcourse.slam.association import mahalanobis_squared

    return mahalanobis_squared(nu, s)


def joint_gate_threshold(pairings: int, confidence: float) -> float:
    """The joint-compatibility gate for ``pairings`` range-bearing pairings: χ² with
    ``2·pairings`` degrees of freedom at ``confidence``."""
    from slamcourse.slam.association import chi2_quantile

    return chi2_quantile(confidence, 2 * int(pairings))


def mistake_joint_sum_of_gates(pairings: int, confidence: float) -> float:
    """The individual two-DOF gates added up: ``k·χ²₂(p)``."""
    return int(pairings) * gate_threshold(2, confidence)


def mistake_joint_single_gate(pairings: int, confidence: float) -> float:
    """One measurement's gate, ``χ²₂(p)``, for the whole set."""
    return gate_threshold(2, confidence)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def gate_clear(d2: float, dof: int, confidence: float) -> bool:
    """``in_gate``'s domain: ``d² ≥ 0`` and at least 5 % away from the threshold (the prompt
    promises that a quantile correct to about three digits is enough)."""
    if dof not in (1, 2) or not 0.5 <= confidence <= 0.9999 or d2 < 0:
        return False
    threshold = chi2_threshold(int(dof), confidence)
    return abs(d2 - threshold) >= 0.049 * threshold


def nearest_neighbour_valid(
    z: Vector, landmarks: Sequence[Vector], s00: float, s11: float, gate: float
) -> bool:
    """``nearest_neighbour``'s domain: ranges in [0.5, 50] m and bearings within ±1.5 rad (no
    innovation needs wrapping), positive variances and gate, no ``d²`` within 5 % of the gate,
    and no *near* tie between the two best candidates inside the gate. An exact tie (the same
    landmark entered twice) is allowed: the prompt says which index wins."""
    pairs = [z, *landmarks]
    if any(len(p) != 2 for p in pairs):
        return False
    if any(not (0.5 <= p[0] <= 50 and abs(p[1]) <= 1.5) for p in pairs):
        return False
    if not (s00 > 0 and s11 > 0 and gate > 0):
        return False
    d2s = [_d2(z, h, s00, s11) for h in landmarks]
    if any(abs(d - gate) < 0.05 * gate for d in d2s):
        return False
    inside = sorted(set(d for d in d2s if d < gate))
    return len(inside) < 2 or inside[1] - inside[0] > 0.05 * gate
