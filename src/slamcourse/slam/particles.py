"""Particle filters and FastSLAM 1.0: sampling, weighting, resampling, one landmark's EKF.

Conventions: a pose is ``(x, y, θ)`` in metres and radians, headings wrapped into (−π, π]. An
odometry reading is ``u = (δrot1, δtrans, δrot2)`` (turn, drive straight, turn), as in the
motion chapter. Its noise follows *Probabilistic Robotics* (Thrun, Burgard and Fox, 2005,
table 5.6), with the four ``alphas`` scaling *variances*:

    σ²rot1  = α1 δrot1² + α2 δtrans²
    σ²trans = α3 δtrans² + α4 (δrot1² + δrot2²)
    σ²rot2  = α1 δrot2² + α2 δtrans²

and each of the three controls perturbed by independent zero-mean Gaussian noise of that
standard deviation. A range-bearing observation is ``z = (r, φ)`` with ``φ`` relative to the
robot's heading; its noise covariance is ``Q`` (2×2).

Stochastic pieces take their randomness as an argument (a numpy ``Generator`` or a uniform
number), so every function here is deterministic given its arguments.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam.se2 import wrap_angle

Array = NDArray[np.float64]
Vec = Sequence[float] | NDArray[Any]
"""A pose, a control, a landmark or an observation: a sequence or a numpy array."""


# --- sampling the motion model -------------------------------------------------------------------


def odometry_noise_sd(u: Vec, alphas: Vec) -> tuple[float, float, float]:
    """The standard deviations ``(σrot1, σtrans, σrot2)`` of the noise on the three controls."""
    rot1, trans, rot2 = (float(v) for v in u)
    a1, a2, a3, a4 = (float(a) for a in alphas)
    return (
        math.sqrt(a1 * rot1**2 + a2 * trans**2),
        math.sqrt(a3 * trans**2 + a4 * (rot1**2 + rot2**2)),
        math.sqrt(a1 * rot2**2 + a2 * trans**2),
    )


def move(pose: Vec, u: Vec) -> Array:
    """The noise-free odometry step: turn by δrot1, drive δtrans, turn by δrot2."""
    x, y, theta = (float(v) for v in pose)
    rot1, trans, rot2 = (float(v) for v in u)
    heading = theta + rot1
    return np.array(
        [
            x + trans * math.cos(heading),
            y + trans * math.sin(heading),
            wrap_angle(heading + rot2),
        ]
    )


def sample_motion(
    pose: Vec,
    u: Vec,
    alphas: Vec,
    n: int,
    rng: np.random.Generator,
) -> Array:
    """``n`` poses (n×3) sampled from the odometry motion model: each control perturbed by its
    own Gaussian noise, the same noisy δrot1 used for the direction of travel and the heading."""
    sd = odometry_noise_sd(u, alphas)
    noise = rng.normal(size=(int(n), 3)) * np.array(sd)
    rot1 = float(u[0]) + noise[:, 0]
    trans = float(u[1]) + noise[:, 1]
    rot2 = float(u[2]) + noise[:, 2]
    x, y, theta = (float(v) for v in pose)
    heading = theta + rot1
    out = np.empty((int(n), 3))
    out[:, 0] = x + trans * np.cos(heading)
    out[:, 1] = y + trans * np.sin(heading)
    out[:, 2] = np.remainder(heading + rot2 + math.pi, 2 * math.pi) - math.pi
    out[:, 2][out[:, 2] == -math.pi] = math.pi
    return out


def noise_from_samples(pose: Vec, u: Vec, samples: ArrayLike) -> Array:
    """The noise ``(ε_rot1, ε_trans, ε_rot2)`` each sampled pose (n×3) must have been drawn
    with: the motion model inverted. Exact while every sampled δtrans is positive and every
    rotation noise lies within ±π."""
    x, y, theta = (float(v) for v in pose)
    rot1, trans, rot2 = (float(v) for v in u)
    p = np.asarray(samples, dtype=float).reshape(-1, 3)
    dx, dy = p[:, 0] - x, p[:, 1] - y
    direction = np.arctan2(dy, dx)
    eps = np.empty_like(p)
    eps[:, 0] = _wrap(direction - theta - rot1)
    eps[:, 1] = np.hypot(dx, dy) - trans
    eps[:, 2] = _wrap(p[:, 2] - direction - rot2)
    return eps


def _wrap(a: Array) -> Array:
    return np.asarray(np.remainder(a + math.pi, 2 * math.pi) - math.pi, dtype=float)


@dataclass(frozen=True)
class NoiseTest:
    """Thresholds of :func:`check_gaussian_noise` for a per-call false-rejection probability
    ``alpha``: Bonferroni over at most :data:`TESTS` exact tests, each at ``alpha / TESTS``."""

    alpha: float

    @property
    def each(self) -> float:
        return self.alpha / TESTS

    @property
    def z(self) -> float:
        """Two-sided standard-normal threshold of one test."""
        return _normal_isf(self.each / 2)

    def chi2_window(self, n: int) -> tuple[float, float]:
        """Two-sided window of a χ² with ``n`` degrees of freedom."""
        return _chi2_window(self.each / 2, n)


@lru_cache(maxsize=64)  # a batch judges thousands of samples with a handful of (α, n)
def _normal_isf(p: float) -> float:
    from scipy.stats import norm  # type: ignore[import-untyped]

    return float(norm.isf(p))


@lru_cache(maxsize=4096)
def _chi2_window(p: float, n: int) -> tuple[float, float]:
    from scipy.stats import chi2

    return float(chi2.ppf(p, n)), float(chi2.isf(p, n))


TESTS = 9
"""Three means, three variances, three pairwise independences."""
ZERO_NOISE = 1e-9
"""A control whose noise has standard deviation 0 must come back within this of its value."""
NAMES = ("δrot1", "δtrans", "δrot2")


def check_gaussian_noise(eps: ArrayLike, sd: Vec, alpha: float) -> str | None:
    """Whether noise samples ``eps`` (n×3) are independent draws of N(0, sd_k²), by exact tests
    that a true sample fails with probability at most ``alpha`` in all; ``None`` when accepted,
    else why not. Standardised, ``z = ε / σ``:

    - each mean: ``Σz / √n`` is N(0, 1);
    - each variance: ``Σz²`` is χ² with ``n`` degrees of freedom;
    - each pair ``j ≠ k``: ``Σ z_j z_k / √(Σ z_k²)`` is N(0, 1) (exactly: given ``z_k``, the sum
      is Gaussian with variance ``Σ z_k²``), which a shared or correlated noise fails.

    A control with ``σ = 0`` must have no noise at all. Deterministic: no randomness here.
    """
    e = np.asarray(eps, dtype=float).reshape(-1, 3)
    n = len(e)
    test = NoiseTest(alpha)
    z = np.zeros_like(e)
    live = []
    for k in range(3):
        if sd[k] == 0:
            worst = float(np.max(np.abs(e[:, k]))) if n else 0.0
            if worst > ZERO_NOISE:
                return (
                    f"with these alphas {NAMES[k]} has no noise (standard deviation 0), "
                    f"but your samples imply noise on it of up to {worst:.3g}"
                )
            continue
        z[:, k] = e[:, k] / sd[k]
        live.append(k)
    if n == 0:
        return None
    limit = test.z
    low, high = test.chi2_window(n)
    for k in live:
        mean = float(np.sum(z[:, k]) / math.sqrt(n))
        if abs(mean) > limit:
            return (
                f"the noise on {NAMES[k]} your samples imply has mean "
                f"{np.mean(e[:, k]):.3g}, {abs(mean):.1f} standard errors from 0 "
                f"(accepted: {limit:.2f})"
            )
        ratio = math.sqrt(float(np.mean(z[:, k] ** 2)))
        square = float(np.sum(z[:, k] ** 2))
        if not low <= square <= high:
            return (
                f"the noise on {NAMES[k]} your samples imply has a standard deviation "
                f"{ratio:.3g} times the model's {sd[k]:.3g} (a χ² test with {n} degrees of "
                f"freedom rejects it)"
            )
    for j in live:
        for k in live:
            if j >= k:
                continue
            scale = math.sqrt(float(np.sum(z[:, k] ** 2)))
            stat = float(np.sum(z[:, j] * z[:, k]) / scale) if scale > 0 else 0.0
            if abs(stat) > limit:
                corr = float(np.corrcoef(e[:, j], e[:, k])[0, 1]) if n > 1 else float("nan")
                return (
                    f"the noises on {NAMES[j]} and {NAMES[k]} your samples imply are not "
                    f"independent (correlation {corr:.3g}, test statistic {abs(stat):.1f}, "
                    f"accepted: {limit:.2f}): draw each control's noise separately"
                )
    return None


# --- weights ------------------------------------------------------------------------------------


def range_bearing(pose: Vec, landmark: Vec) -> Array:
    """The predicted observation ``(r, φ)`` of a landmark ``(x, y)`` from a pose."""
    x, y, theta = (float(v) for v in pose)
    dx, dy = float(landmark[0]) - x, float(landmark[1]) - y
    return np.array([math.hypot(dx, dy), wrap_angle(math.atan2(dy, dx) - theta)])


def innovation(z: Vec, z_hat: Vec) -> Array:
    """``z − ẑ`` with the bearing difference wrapped into (−π, π]."""
    return np.array([float(z[0]) - float(z_hat[0]), wrap_angle(float(z[1]) - float(z_hat[1]))])


def gaussian_likelihood(nu: ArrayLike, cov: ArrayLike) -> float:
    """The density of N(0, cov) at ``nu``: ``exp(−½ νᵀ S⁻¹ ν) / √det(2π S)``."""
    v = np.asarray(nu, dtype=float)
    s = np.asarray(cov, dtype=float)
    return float(
        math.exp(-0.5 * float(v @ np.linalg.solve(s, v)))
        / math.sqrt(np.linalg.det(2 * math.pi * s))
    )


def normalise(weights: ArrayLike) -> Array:
    w = np.asarray(weights, dtype=float)
    return np.asarray(w / w.sum(), dtype=float)


def effective_sample_size(weights: ArrayLike) -> float:
    """``N_eff = 1 / Σ w̄²`` of the normalised weights: N for equal weights, 1 for one."""
    w = normalise(weights)
    return float(1.0 / np.sum(w**2))


# --- resampling ---------------------------------------------------------------------------------


def low_variance_resample(weights: ArrayLike, u: float) -> NDArray[np.int64]:
    """Low-variance (systematic) resampling with the one uniform number ``u`` in [0, 1): the N
    thresholds ``(u + m) / N`` walk once through the normalised cumulative weights; particle
    ``m`` takes the first index whose cumulative weight reaches its threshold."""
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    thresholds = (float(u) + np.arange(n)) / n
    idx = np.searchsorted(c, thresholds, side="left")
    return np.minimum(idx, n - 1).astype(np.int64)


def nearest_tie(weights: ArrayLike, u: float) -> float:
    """How close any threshold ``(u + m) / N`` comes to a normalised cumulative weight (or to 0):
    where they meet, correct methods may pick either neighbour (a float rounding apart)."""
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    thresholds = (float(u) + np.arange(n)) / n
    idx = np.searchsorted(c, thresholds)
    lo = np.abs(thresholds - c[np.maximum(idx - 1, 0)])
    hi = np.abs(thresholds - c[np.minimum(idx, n)])
    return float(min(lo.min(), hi.min()))


def multinomial_resample(weights: ArrayLike, rng: np.random.Generator) -> NDArray[np.int64]:
    """N independent draws from the normalised weights (for comparison)."""
    w = normalise(weights)
    n = len(w)
    idx = np.searchsorted(np.cumsum(w), rng.uniform(size=n), side="left")
    return np.minimum(idx, n - 1).astype(np.int64)


def copies(indices: ArrayLike, n: int) -> NDArray[np.int64]:
    """How many copies of each of ``n`` particles a resampling kept."""
    return np.bincount(np.asarray(indices, dtype=np.int64), minlength=n).astype(np.int64)


# --- FastSLAM 1.0: one landmark's EKF -----------------------------------------------------------


def observation_jacobian(pose: Vec, landmark: Vec) -> Array:
    """``H = ∂(r, φ)/∂(landmark x, y)`` at the landmark's mean (2×2)."""
    x, y, _ = (float(v) for v in pose)
    dx, dy = float(landmark[0]) - x, float(landmark[1]) - y
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    return np.array([[dx / r, dy / r], [-dy / q, dx / q]])


@dataclass(frozen=True)
class LandmarkUpdate:
    """One landmark's EKF after an observation, and the particle's weight factor."""

    mean: Array
    cov: Array
    weight: float


def landmark_update(
    pose: Vec,
    mean: Vec,
    cov: ArrayLike,
    z: Vec,
    q: ArrayLike,
) -> LandmarkUpdate:
    """FastSLAM 1.0's update of one landmark's 2×2 EKF given the particle's pose, and the
    weight factor ``N(ν; 0, S)`` with ``S = H Σ Hᵀ + Q``, the innovation ``ν`` wrapped."""
    mu = np.asarray(mean, dtype=float)
    sigma = np.asarray(cov, dtype=float)
    qm = np.asarray(q, dtype=float)
    h = observation_jacobian(pose, mu)
    nu = innovation(z, range_bearing(pose, mu))
    s = h @ sigma @ h.T + qm
    k = sigma @ h.T @ np.linalg.inv(s)
    new_mean = mu + k @ nu
    new_cov = (np.eye(2) - k @ h) @ sigma
    return LandmarkUpdate(new_mean, 0.5 * (new_cov + new_cov.T), gaussian_likelihood(nu, s))
