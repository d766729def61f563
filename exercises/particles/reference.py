"""Reference answers for chapter ``particles``: sampling, weights, resampling, FastSLAM 1.0.

The mathematics lives in :mod:`slamcourse.slam.particles`. Functions whose name starts with
``mistake_`` compute the answer of a named misconception. ``judge_sample_motion`` is the
statistical judge of the stochastic code exercise ``sample-motion``: it inverts the motion
model to recover the noise each returned pose was drawn with, and tests that noise against the
model exactly (see :func:`slamcourse.slam.particles.check_gaussian_noise`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from slamcourse.slam import particles as pf

# --- numeric exercises ------------------------------------------------------------------------


def trans_noise_sd(r1: float, t: float, r2: float, a3: float, a4: float) -> float:
    """σ_trans = √(α3 δtrans² + α4 (δrot1² + δrot2²))."""
    return pf.odometry_noise_sd((r1, t, r2), (0.0, 0.0, a3, a4))[1]


def mistake_sd_variance(r1: float, t: float, r2: float, a3: float, a4: float) -> float:
    """The variance, given as the standard deviation."""
    return trans_noise_sd(r1, t, r2, a3, a4) ** 2


def mistake_sd_abs(r1: float, t: float, r2: float, a3: float, a4: float) -> float:
    """α3 |δtrans| + α4 (|δrot1| + |δrot2|): the other book's standard-deviation form."""
    return a3 * abs(t) + a4 * (abs(r1) + abs(r2))


def mistake_sd_no_rot2(r1: float, t: float, r2: float, a3: float, a4: float) -> float:
    """The second turn left out of the translation noise."""
    return math.sqrt(a3 * t**2 + a4 * r1**2)


def _weights3(
    zr: float, zp: float, r1: float, p1: float, r2: float, p2: float, r3: float, p3: float,
    sr: float, sp: float, *, wrap: bool = True, scaled: bool = True,
) -> list[float]:  # fmt: skip
    q = np.diag([sr**2, sp**2]) if scaled else np.eye(2)
    out = []
    for r, p in ((r1, p1), (r2, p2), (r3, p3)):
        nu = pf.innovation((zr, zp), (r, p)) if wrap else np.array([zr - r, zp - p])
        out.append(pf.gaussian_likelihood(nu, q))
    return out


def particle_weight(
    zr: float, zp: float, r1: float, p1: float, r2: float, p2: float, r3: float, p3: float,
    sr: float, sp: float, **_: float,
) -> float:  # fmt: skip
    """Particle 1's normalised weight: its likelihood over the sum of all three."""
    w = _weights3(zr, zp, r1, p1, r2, p2, r3, p3, sr, sp)
    return w[0] / sum(w)


def mistake_weight_no_wrap(
    zr: float, zp: float, r1: float, p1: float, r2: float, p2: float, r3: float, p3: float,
    sr: float, sp: float, **_: float,
) -> float:  # fmt: skip
    w = _weights3(zr, zp, r1, p1, r2, p2, r3, p3, sr, sp, wrap=False)
    return w[0] / sum(w)


def mistake_weight_unscaled(
    zr: float, zp: float, r1: float, p1: float, r2: float, p2: float, r3: float, p3: float,
    sr: float, sp: float, **_: float,
) -> float:  # fmt: skip
    w = _weights3(zr, zp, r1, p1, r2, p2, r3, p3, sr, sp, scaled=False)
    return w[0] / sum(w)


def mistake_weight_unnormalised(
    zr: float, zp: float, r1: float, p1: float, r2: float, p2: float, r3: float, p3: float,
    sr: float, sp: float, **_: float,
) -> float:  # fmt: skip
    return _weights3(zr, zp, r1, p1, r2, p2, r3, p3, sr, sp)[0]


def ess(w1: float, w2: float, w3: float, w4: float, w5: float) -> float:
    return pf.effective_sample_size([w1, w2, w3, w4, w5])


def mistake_ess_unnormalised(w1: float, w2: float, w3: float, w4: float, w5: float) -> float:
    """1 / Σ w² of the raw weights."""
    return 1.0 / sum(w * w for w in (w1, w2, w3, w4, w5))


def mistake_ess_sum_squares(w1: float, w2: float, w3: float, w4: float, w5: float) -> float:
    """Σ w̄², without taking the reciprocal."""
    return 1.0 / ess(w1, w2, w3, w4, w5)


def resampled(w1: int, w2: int, w3: int, w4: int, w5: int, u: float) -> list[int]:
    return pf.low_variance_resample([w1, w2, w3, w4, w5], u).tolist()  # type: ignore[no-any-return]


def mistake_resampled_one_based(w1: int, w2: int, w3: int, w4: int, w5: int, u: float) -> list[int]:
    return [i + 1 for i in resampled(w1, w2, w3, w4, w5, u)]


def mistake_resampled_u_unscaled(
    w1: int, w2: int, w3: int, w4: int, w5: int, u: float
) -> list[int]:
    """Thresholds ``u + m/N``: the uniform number not divided by N."""
    return _unscaled([w1, w2, w3, w4, w5], u).tolist()  # type: ignore[no-any-return]


def _unscaled(weights: Sequence[float], u: float) -> Any:
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w) / w.sum()
    return np.minimum(np.searchsorted(c, float(u) + np.arange(n) / n), n - 1)


def mistake_resampled_unnormalised(
    w1: int, w2: int, w3: int, w4: int, w5: int, u: float
) -> list[int]:
    """The raw cumulative weights compared with thresholds in [0, 1)."""
    return _unnormalised([w1, w2, w3, w4, w5], u).tolist()  # type: ignore[no-any-return]


def _unnormalised(weights: Sequence[float], u: float) -> Any:
    w = np.asarray(weights, dtype=float)
    n = len(w)
    c = np.cumsum(w)
    return np.minimum(np.searchsorted(c, (float(u) + np.arange(n)) / n), n - 1)


def fastslam_numbers(m: int, k: int) -> int:
    """Numbers FastSLAM 1.0 stores: per particle a pose (3), a weight (1), and per landmark a
    mean (2) and a full 2×2 covariance (4)."""
    return m * (3 + 1 + k * (2 + 4))


def mistake_fastslam_joint(m: int, k: int) -> int:
    """Per particle a joint map covariance (2K × 2K), as if each particle ran an EKF-SLAM."""
    return m * (3 + 1 + 2 * k + (2 * k) ** 2)


def mistake_fastslam_one_particle(m: int, k: int) -> int:
    return fastslam_numbers(1, k)


def mistake_fastslam_no_weight(m: int, k: int) -> int:
    return m * (3 + 6 * k)


# --- code: low_variance_resample ------------------------------------------------------------


def low_variance_resample(weights: Sequence[float], u: float) -> list[int]:
    return pf.low_variance_resample(weights, u).tolist()  # type: ignore[no-any-return]


def mistake_lvr_u_unscaled(weights: Sequence[float], u: float) -> list[int]:
    return _unscaled(weights, u).tolist()  # type: ignore[no-any-return]


def mistake_lvr_unnormalised(weights: Sequence[float], u: float) -> list[int]:
    return _unnormalised(weights, u).tolist()  # type: ignore[no-any-return]


def mistake_lvr_one_based(weights: Sequence[float], u: float) -> list[int]:
    return [i + 1 for i in low_variance_resample(weights, u)]


TIE = 1e-9
"""Inputs where a threshold comes this close to a cumulative weight are outside the domain: there
correct methods may pick either neighbour, a float rounding apart."""


def resample_valid(weights: Sequence[float], u: float) -> bool:
    """``low_variance_resample``'s domain: 1–400 weights in [0, 100] with a positive sum, u in
    [0, 1), and no threshold within 1e-9 of a cumulative weight (or of 0)."""
    try:
        w = [float(v) for v in weights]
    except (TypeError, ValueError):
        return False
    if not 1 <= len(w) <= 400 or any(not 0 <= v <= 100 for v in w) or sum(w) <= 0:
        return False
    if not 0 <= float(u) < 1:
        return False
    return pf.nearest_tie(w, u) > TIE


def resample_inputs() -> Any:
    """Weights spread over eight orders of magnitude (unnormalised likelihoods), a quarter of
    them zero, and one uniform number."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    weight = st.one_of(
        st.just(0.0),
        real(-6.0, 2.0).map(lambda e: float(f"{10**e:.12g}")),
        real(0.0, 1.0),
    ).filter(lambda v: 0 <= v <= 100)
    return st.fixed_dictionaries(
        {"weights": st.lists(weight, min_size=1, max_size=300), "u": real(0.0, 0.999999)}
    ).filter(lambda d: resample_valid(**d))


# --- code: sample_motion (judged) -----------------------------------------------------------

PER_CALL = 1e-6
"""A correct sampler fails one call with at most this probability (the tests' 0.99e-6, and the
tail events the domain excludes, which a correct sampler meets with under 1e-8)."""
WHOLE_CHECK = 2e-4
"""... and the whole check (at most 200 calls, pinned by the chapter's tests)."""


def sample_motion(
    pose: Sequence[float], u: Sequence[float], alphas: Sequence[float], n: int, seed: int
) -> list[list[float]]:
    """One right answer (of many): ``n`` poses drawn with ``np.random.default_rng(seed)``."""
    rng = np.random.default_rng(int(seed))
    return pf.sample_motion(pose, u, alphas, int(n), rng).tolist()  # type: ignore[no-any-return]


def judge_sample_motion(got: Any, expected: Any, kwargs: dict[str, Any]) -> str | None:
    """Accept ``got`` (n×3, plain data) when its headings lie in [−π, π] and the noise it
    implies passes the exact tests of ``check_gaussian_noise`` at ``0.99·PER_CALL``."""
    p = np.asarray(got, dtype=float)
    headings = p[:, 2] if p.size else p
    bad = np.flatnonzero(np.abs(headings) > math.pi)
    if bad.size:
        return (
            f"row {int(bad[0])}: the heading {float(headings[bad[0]])!r} is outside "
            "[-π, π]; wrap it"
        )
    eps = pf.noise_from_samples(kwargs["pose"], kwargs["u"], p)
    sd = pf.odometry_noise_sd(kwargs["u"], kwargs["alphas"])
    return pf.check_gaussian_noise(eps, sd, 0.99 * PER_CALL)


def motion_valid(
    pose: Sequence[float], u: Sequence[float], alphas: Sequence[float], n: int, seed: int
) -> bool:
    """``sample_motion``'s domain: positions in [−50, 50] m, δtrans in [0.1, 2] m, every alpha
    in [0, 0.05], n in [1, 2000], and noise small enough that a correct sample can be inverted:
    σ_trans ≤ δtrans / 8 (δ̂trans stays positive) and σ_rot1, σ_rot2 ≤ 0.4 rad."""
    try:
        x, y, theta = (float(v) for v in pose)
        rot1, trans, rot2 = (float(v) for v in u)
        a = [float(v) for v in alphas]
    except (TypeError, ValueError):
        return False
    if len(a) != 4 or not (abs(x) <= 50 and abs(y) <= 50 and abs(theta) <= math.pi):
        return False
    if not (0.1 <= trans <= 2 and abs(rot1) <= math.pi and abs(rot2) <= math.pi):
        return False
    if any(not 0 <= v <= 0.05 for v in a) or not 1 <= int(n) <= 2000:
        return False
    s1, s2, s3 = pf.odometry_noise_sd((rot1, trans, rot2), a)
    return s2 <= trans / 8 and s1 <= 0.4 and s3 <= 0.4


def motion_inputs() -> Any:
    """Poses anywhere in the square, turns anywhere in [−π, π], drives of 0.1–2 m, and alphas
    that keep the model invertible (a fifth of them exactly zero)."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    def alpha(high: float) -> Any:
        return st.one_of(st.just(0.0), real(1e-4, high))

    return st.fixed_dictionaries(
        {
            "pose": st.tuples(real(-50, 50), real(-50, 50), real(-math.pi, math.pi)),
            "u": st.tuples(real(-math.pi, math.pi), real(0.1, 2.0), real(-math.pi, math.pi)),
            "alphas": st.tuples(alpha(0.015), alpha(0.02), alpha(0.01), alpha(0.0005)),
            "n": st.integers(100, 500),
            "seed": st.integers(0, 10**6),
        }
    ).filter(lambda d: motion_valid(**d))


# --- FastSLAM: one landmark's EKF (numeric) -----------------------------------------------------


def landmark_mean(
    mx: float, my: float, s: float, zr: float, zp: float, sr: float, sp: float, **_: float
) -> list[float]:
    """The landmark's mean after the update, the particle at the origin facing along x."""
    upd = pf.landmark_update(
        (0.0, 0.0, 0.0), (mx, my), s * np.eye(2), (zr, zp), np.diag([sr**2, sp**2])
    )
    return upd.mean.tolist()  # type: ignore[no-any-return]


def landmark_weight(
    mx: float, my: float, s: float, zr: float, zp: float, sr: float, sp: float, **_: float
) -> float:
    upd = pf.landmark_update(
        (0.0, 0.0, 0.0), (mx, my), s * np.eye(2), (zr, zp), np.diag([sr**2, sp**2])
    )
    return upd.weight


def mistake_landmark_full_trust(
    mx: float, my: float, s: float, zr: float, zp: float, sr: float, sp: float, **_: float
) -> list[float]:
    """The landmark moved all the way to the measurement (gain ``H⁻¹``, as if Σ ≫ Q)."""
    return [zr * math.cos(zp), zr * math.sin(zp)]


def mistake_landmark_unchanged(
    mx: float, my: float, s: float, zr: float, zp: float, sr: float, sp: float, **_: float
) -> list[float]:
    return [mx, my]


def mistake_landmark_q_for_s(
    mx: float, my: float, s: float, zr: float, zp: float, sr: float, sp: float, **_: float
) -> list[float]:
    """The gain computed with ``S = Q`` (the landmark's own uncertainty left out of S)."""
    mu = np.array([mx, my])
    h = pf.observation_jacobian((0.0, 0.0, 0.0), mu)
    nu = pf.innovation((zr, zp), pf.range_bearing((0.0, 0.0, 0.0), mu))
    k = s * np.eye(2) @ h.T @ np.linalg.inv(np.diag([sr**2, sp**2]))
    return (mu + k @ nu).tolist()  # type: ignore[no-any-return]
