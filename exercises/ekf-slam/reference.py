"""Reference answers for chapter ``ekf-slam``: the EKF update and landmark initialisation.

The mathematics lives in :mod:`slamcourse.slam.ekfslam` (``kalman_gain``, ``update_covariance``,
``inverse_observation``, its Jacobians ``G_r`` and ``G_z``, ``augment``); angles are wrapped with
:func:`slamcourse.slam.se2.wrap_angle`. Functions whose name starts with ``mistake_`` compute the
answer of a named misconception; Hypothesis strategies import Hypothesis inside their body.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import ekfslam

Matrix = NDArray[np.float64]


# --- the gain in one dimension ----------------------------------------------------------------


def scalar_gain(var_prior: float, var_meas: float) -> float:
    """``K = P Hᵀ S⁻¹`` with ``H = 1``: ``p / (p + r)``."""
    return float(ekfslam.kalman_gain([[var_prior]], [[1.0]], [[var_meas]])[0, 0])


def mistake_gain_swapped(var_prior: float, var_meas: float) -> float:
    """``r / (p + r)``: the weight of the prediction, not of the measurement."""
    return var_meas / (var_prior + var_meas)


def mistake_gain_ratio(var_prior: float, var_meas: float) -> float:
    """``p / r``: the prior variance divided by the noise, ``S`` without ``P``."""
    return var_prior / var_meas


def scalar_posterior(var_prior: float, var_meas: float) -> float:
    """``P⁺ = (1 − K) p = p r / (p + r)``."""
    return float(ekfslam.update_covariance([[var_prior]], [[1.0]], [[var_meas]])[0, 0])


# --- a correlated update ----------------------------------------------------------------------


def correlated_update(pxx: float, pxy: float, pyy: float, rxx: float) -> float:
    """``P⁺_yy`` after measuring ``x`` alone (``H = [1, 0]``, noise ``rxx``)."""
    p = [[pxx, pxy], [pxy, pyy]]
    return float(ekfslam.update_covariance(p, [[1.0, 0.0]], [[rxx]])[1, 1])


def mistake_unmeasured_unchanged(pxx: float, pxy: float, pyy: float, rxx: float) -> float:
    """``P_yy``: the entry not measured left alone."""
    return pyy


def mistake_correlated_no_noise(pxx: float, pxy: float, pyy: float, rxx: float) -> float:
    """``P_yy − P_xy² / P_xx``: ``S`` without the measurement noise."""
    return pyy - pxy * pxy / pxx


def mistake_correlated_not_squared(pxx: float, pxy: float, pyy: float, rxx: float) -> float:
    """``P_yy − P_xy / (P_xx + R)``: the gain times ``H`` without the second ``P_xy``."""
    return pyy - pxy / (pxx + rxx)


# --- the new landmark -------------------------------------------------------------------------


def landmark_position(x: float, y: float, t: float, rng: float, brg: float) -> list[float]:
    """``g(x_r, z) = (x + r cos(θ + φ), y + r sin(θ + φ))`` in metres."""
    return ekfslam.inverse_observation((x, y, t), (rng, brg)).tolist()  # type: ignore[no-any-return]


def mistake_position_heading_ignored(
    x: float, y: float, t: float, rng: float, brg: float
) -> list[float]:
    """The bearing used as a world direction: ``θ`` left out."""
    return [x + rng * math.cos(brg), y + rng * math.sin(brg)]


def mistake_position_minus_bearing(
    x: float, y: float, t: float, rng: float, brg: float
) -> list[float]:
    """``θ − φ``: the bearing subtracted as in ``φ = atan2(Δy, Δx) − θ`` read backwards."""
    return [x + rng * math.cos(t - brg), y + rng * math.sin(t - brg)]


def mistake_position_robot_frame(
    x: float, y: float, t: float, rng: float, brg: float
) -> list[float]:
    """The landmark in the robot's frame: the robot's position not added."""
    return [rng * math.cos(t + brg), rng * math.sin(t + brg)]


def new_entries(landmarks: int) -> int:
    """Entries of ``P'`` not copied from ``P``: ``(n + 2)² − n²`` with ``n = 3 + 2N``."""
    n = 3 + 2 * int(landmarks)
    mu = np.zeros(n)
    p = np.eye(n)
    _, out = ekfslam.augment(mu, p, (1.0, 0.0), np.eye(2))
    return int(out.size - p.size)


def mistake_entries_block_only(landmarks: int) -> int:
    """Only the new 2×2 landmark block."""
    return 4


def mistake_entries_total(landmarks: int) -> int:
    """All entries of the augmented matrix, ``(n + 2)²``."""
    return (5 + 2 * int(landmarks)) ** 2


def mistake_entries_one_side(landmarks: int) -> int:
    """One cross block and the landmark block, as if ``P'`` were stored as a triangle."""
    return 2 * (3 + 2 * int(landmarks)) + 4


def cross_covariance(
    t: float, rng: float, brg: float, vx: float, vy: float, vt: float, cxt: float
) -> Matrix:
    """``P_Lr = G_r P_rr`` (2×3) with ``P_rr = [[vx, 0, cxt], [0, vy, 0], [cxt, 0, vt]]``."""
    p_rr = np.array([[vx, 0.0, cxt], [0.0, vy, 0.0], [cxt, 0.0, vt]])
    _, out = ekfslam.augment([0.0, 0.0, t], p_rr, (rng, brg), np.eye(2))
    return np.asarray(out[3:, :3])


def mistake_cross_zero(
    t: float, rng: float, brg: float, vx: float, vy: float, vt: float, cxt: float
) -> Matrix:
    """A new landmark taken as independent of the robot."""
    return np.zeros((2, 3))


def mistake_cross_heading_only(
    t: float, rng: float, brg: float, vx: float, vy: float, vt: float, cxt: float
) -> Matrix:
    """``G_r`` evaluated at ``θ`` instead of ``θ + φ``."""
    p_rr = np.array([[vx, 0.0, cxt], [0.0, vy, 0.0], [cxt, 0.0, vt]])
    return ekfslam.inverse_jacobian_pose((0.0, 0.0, t), (rng, 0.0)) @ p_rr


def mistake_cross_position_only(
    t: float, rng: float, brg: float, vx: float, vy: float, vt: float, cxt: float
) -> Matrix:
    """Only the identity part of ``G_r``: the landmark copies the robot's position uncertainty."""
    p_rr = np.array([[vx, 0.0, cxt], [0.0, vy, 0.0], [cxt, 0.0, vt]])
    return p_rr[:2, :]


# --- code: update_covariance ------------------------------------------------------------------


def update_covariance(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> Matrix:
    return ekfslam.update_covariance(P, H, R)


def _spd(draw: Any, n: int, scale: float) -> Matrix:
    """A symmetric positive-definite ``n × n`` matrix ``L Lᵀ`` with diagonal around ``scale``."""
    from hypothesis import strategies as st

    diag = st.floats(0.3, 1.0, allow_nan=False, allow_infinity=False)
    off = st.floats(-0.6, 0.6, allow_nan=False, allow_infinity=False)
    low = np.zeros((n, n))
    for i in range(n):
        low[i, i] = draw(diag)
        for k in range(i):
            low[i, k] = draw(off)
    return np.asarray(low @ low.T * scale)


def _state(draw: Any, landmarks: int) -> Matrix:
    """A pose within ±20 m and ``landmarks`` landmarks 1–20 m from it, in any direction."""
    from hypothesis import strategies as st

    coord = st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)
    heading = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    distance = st.floats(1.0, 20.0, allow_nan=False, allow_infinity=False)
    mu = [draw(coord), draw(coord), draw(heading)]
    for _ in range(landmarks):
        d, a = draw(distance), draw(heading)
        mu += [mu[0] + d * math.cos(a), mu[1] + d * math.sin(a)]
    return np.array(mu)


def update_inputs() -> Any:
    """A state with 1–3 landmarks, its covariance (variances 0.01–1), the Jacobian ``H`` of a
    range-bearing measurement of one of them, and a correlated 2×2 noise ``R``."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        landmarks = draw(st.integers(1, 3))
        mu = _state(draw, landmarks)
        j = draw(st.integers(0, landmarks - 1))
        n = mu.size
        p = _spd(draw, n, draw(st.sampled_from([0.01, 0.1, 1.0])))
        r_std = draw(st.floats(0.05, 0.5))
        b_std = draw(st.floats(0.005, 0.05))
        rho = draw(st.floats(-0.8, 0.8))
        r = [[r_std**2, rho * r_std * b_std], [rho * r_std * b_std, b_std**2]]
        return {
            "P": p.tolist(),
            "H": ekfslam.observation_jacobian(mu, j).tolist(),
            "R": r,
        }

    return draw()


def _gain(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
    pm, hm, rm = (np.asarray(a, dtype=float) for a in (P, H, R))
    return pm, hm, rm


def mistake_update_no_inverse(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> Matrix:
    """``K = P Hᵀ``: the innovation covariance never divided out."""
    pm, hm, _ = _gain(P, H, R)
    k = pm @ hm.T
    return np.asarray((np.eye(pm.shape[0]) - k @ hm) @ pm)


def mistake_update_no_noise(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> Matrix:
    """``S = H P Hᵀ``: the measurement taken as exact."""
    pm, hm, _ = _gain(P, H, R)
    return ekfslam.update_covariance_simple(pm, hm, np.zeros((2, 2)))


def mistake_update_joseph_without_krk(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> Matrix:
    """Joseph form without ``K R Kᵀ``: ``(I − K H) P (I − K H)ᵀ``."""
    pm, hm, rm = _gain(P, H, R)
    k = ekfslam.kalman_gain(pm, hm, rm)
    a = np.eye(pm.shape[0]) - k @ hm
    return np.asarray(a @ pm @ a.T)


def mistake_update_diagonal_noise(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> Matrix:
    """``R`` replaced by its diagonal: the range-bearing correlation dropped."""
    pm, hm, rm = _gain(P, H, R)
    return ekfslam.update_covariance(pm, hm, np.diag(np.diag(rm)))


# --- code: augment ----------------------------------------------------------------------------


def augment(mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike) -> Matrix:
    return ekfslam.augment(mu, P, z, R)[1]


def augment_inputs() -> Any:
    """A state with 0–2 landmarks, its covariance (variances 0.01–1, correlated), a measurement
    ``z`` (0.5–30 m, bearing in [−π, π]) and a correlated 2×2 noise ``R``."""
    from hypothesis import strategies as st

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        landmarks = draw(st.integers(0, 2))
        mu = _state(draw, landmarks)
        p = _spd(draw, mu.size, draw(st.sampled_from([0.01, 0.1, 1.0])))
        z = [draw(st.floats(0.5, 30.0)), draw(st.floats(-math.pi, math.pi))]
        r_std = draw(st.floats(0.05, 0.5))
        b_std = draw(st.floats(0.005, 0.05))
        rho = draw(st.floats(-0.8, 0.8))
        r = [[r_std**2, rho * r_std * b_std], [rho * r_std * b_std, b_std**2]]
        return {"mu": mu.tolist(), "P": p.tolist(), "z": z, "R": r}

    return draw()


def _jacobians(mu: Sequence[float], z: Sequence[float]) -> tuple[Matrix, Matrix]:
    pose = [float(v) for v in mu[:3]]
    return ekfslam.inverse_jacobian_pose(pose, z), ekfslam.inverse_jacobian_measurement(pose, z)


def _assemble(p: Matrix, cross: Matrix, block: Matrix) -> Matrix:
    n = p.shape[0]
    out = np.zeros((n + 2, n + 2))
    out[:n, :n] = p
    out[n:, :n] = cross
    out[:n, n:] = cross.T
    out[n:, n:] = block
    return out


def mistake_augment_independent(
    mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike
) -> Matrix:
    """The new landmark uncorrelated with everything: zero cross-covariance blocks."""
    pm, rm = np.asarray(P, dtype=float), np.asarray(R, dtype=float)
    g_r, g_z = _jacobians(mu, z)
    block = g_r @ pm[:3, :3] @ g_r.T + g_z @ rm @ g_z.T
    return _assemble(pm, np.zeros((2, pm.shape[0])), block)


def mistake_augment_noise_not_mapped(
    mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike
) -> Matrix:
    """``R`` added directly to the landmark block: range-bearing noise taken as x-y noise."""
    pm, rm = np.asarray(P, dtype=float), np.asarray(R, dtype=float)
    g_r, _ = _jacobians(mu, z)
    return _assemble(pm, g_r @ pm[:3, :], g_r @ pm[:3, :3] @ g_r.T + rm)


def mistake_augment_pose_block_only(
    mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike
) -> Matrix:
    """Cross-covariance with the pose only (``G_r P_rr``), zero against the older landmarks."""
    pm, rm = np.asarray(P, dtype=float), np.asarray(R, dtype=float)
    g_r, g_z = _jacobians(mu, z)
    cross = np.zeros((2, pm.shape[0]))
    cross[:, :3] = g_r @ pm[:3, :3]
    return _assemble(pm, cross, g_r @ pm[:3, :3] @ g_r.T + g_z @ rm @ g_z.T)


def mistake_augment_heading_only(
    mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike
) -> Matrix:
    """Jacobians evaluated at the robot's heading ``θ`` instead of ``θ + φ``."""
    shifted = [float(mu[0]), float(mu[1]), float(mu[2]) - float(z[1])]
    pm, rm = np.asarray(P, dtype=float), np.asarray(R, dtype=float)
    g_r, g_z = _jacobians(shifted, z)
    return _assemble(pm, g_r @ pm[:3, :], g_r @ pm[:3, :3] @ g_r.T + g_z @ rm @ g_z.T)


# --- a heading update across ±π ---------------------------------------------------------------


def heading_update(theta: float, var_t: float, compass: float, var_c: float) -> float:
    """``θ⁺ = wrap(θ + K·wrap(z − θ))`` for a compass that measures the heading directly
    (``H = 1``, ``K = P / (P + R)``), in (−π, π]."""
    from slamcourse.slam.se2 import wrap_angle

    gain = float(ekfslam.kalman_gain([[var_t]], [[1.0]], [[var_c]])[0, 0])
    return wrap_angle(theta + gain * wrap_angle(compass - theta))


def mistake_heading_unwrapped(theta: float, var_t: float, compass: float, var_c: float) -> float:
    """The innovation ``z − θ`` not wrapped: a step of almost 2π the wrong way."""
    return theta + var_t / (var_t + var_c) * (compass - theta)


def mistake_heading_gain_swapped(theta: float, var_t: float, compass: float, var_c: float) -> float:
    """The gain ``R / (P + R)``: the update moves by the prediction's weight."""
    from slamcourse.slam.se2 import wrap_angle

    return theta + var_c / (var_t + var_c) * wrap_angle(compass - theta)


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


def augment_valid(mu: Sequence[float], P: ArrayLike, z: Sequence[float], R: ArrayLike) -> bool:
    """``augment``'s domain: a state of ``3 + 2N`` numbers (0 ≤ N ≤ 2) with its symmetric
    positive-definite covariance, a range in [0.5, 30] m and a bearing in [−π, π], and a
    symmetric positive-definite 2×2 ``R``."""
    m = np.asarray(mu, dtype=float)
    if m.ndim != 1 or m.size not in (3, 5, 7) or len(z) != 2:
        return False
    if not (0.5 <= float(z[0]) <= 30 and abs(float(z[1])) <= math.pi):
        return False
    return _positive_definite(P, m.size) and _positive_definite(R, 2)


def update_valid(P: ArrayLike, H: ArrayLike, R: ArrayLike) -> bool:
    """``update_covariance``'s domain: ``P`` symmetric positive definite of size ``3 + 2N``
    (1 ≤ N ≤ 3), ``H`` of shape 2 × n with finite entries, ``R`` symmetric positive definite."""
    p = np.asarray(P, dtype=float)
    h = np.asarray(H, dtype=float)
    if p.ndim != 2 or p.shape[0] not in (5, 7, 9) or h.shape != (2, p.shape[0]):
        return False
    if not np.all(np.isfinite(h)) or not np.any(h):
        return False
    used = set(np.flatnonzero(np.any(h != 0, axis=0)).tolist()) - {0, 1, 2}
    if used and not any(used <= {3 + 2 * j, 4 + 2 * j} for j in range((p.shape[0] - 3) // 2)):
        return False  # the prompt: nonzero only in the pose's columns and one landmark's two
    return _positive_definite(p, p.shape[0]) and _positive_definite(R, 2)


# --- code: one whole EKF-SLAM step (issue 16) -------------------------------------------------

from slamcourse.slam import ekf as _ekf  # noqa: E402
from slamcourse.slam.se2 import wrap_angle as _wrap  # noqa: E402


def slam_predict(
    mu: ArrayLike, P: ArrayLike, u: Sequence[float], M: ArrayLike
) -> tuple[Matrix, Matrix]:
    """The prediction on the whole state: the pose moves by ``u``, ``P`` becomes
    ``F P Fᵀ + F_x V M Vᵀ F_xᵀ`` with ``F = blockdiag(G, I)``; landmarks stay where they are."""
    m = np.array(mu, dtype=float)
    p = np.array(P, dtype=float)
    pose = [float(v) for v in m[:3]]
    g = _ekf.jacobian_state(pose, u)
    v = _ekf.jacobian_control(pose, u)
    m[:3] = _ekf.odometry_step(pose, u)
    p[:3, :] = g @ p[:3, :]
    p[:, :3] = p[:, :3] @ g.T
    p[:3, :3] += v @ np.asarray(M, dtype=float) @ v.T
    return m, p


def ekf_slam_step(
    mu: ArrayLike,
    Sigma: ArrayLike,
    u: Sequence[float],
    M: ArrayLike,
    z: ArrayLike,
    ids: Sequence[int],
    R: ArrayLike,
) -> Matrix:
    """Predict with ``u``, then each measurement in turn: an update for a mapped landmark,
    augmentation for a new one. Returns ``[μ'; Σ']`` stacked, shape (n' + 1, n')."""
    m, p = slam_predict(mu, Sigma, u, M)
    for zk, j in zip(np.asarray(z, dtype=float).reshape(-1, 2), ids, strict=True):
        j = int(j)
        if 3 + 2 * j < m.size:
            h = ekfslam.observe(m[:3], m[3 + 2 * j : 5 + 2 * j])
            m, p = ekfslam.update(m, p, zk, h, ekfslam.observation_jacobian(m, j), R)
        else:
            m, p = ekfslam.augment(m, p, zk, R)
    return np.vstack([m, p])


def ekf_step_inputs() -> Any:
    """A state with 1–3 landmarks within 20 m of the robot, a covariance built like
    EKF-SLAM's (pose σ 0.05–0.5 m and 0.01–0.2 rad, landmarks tied to it), a motion
    (turns within ±π, 0–3 m), its 3×3 noise, 1–3 measurements of distinct landmarks (a
    mapped one or the next new one, at most two new) taken from a true pose near the
    predicted one, and a possibly correlated ``R``."""
    from hypothesis import strategies as st

    from slamcourse.grading.strategies import real

    @st.composite
    def draw(draw: Any) -> dict[str, Any]:
        rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
        known = draw(st.integers(1, 3))
        pose = [draw(real(-20, 20)), draw(real(-20, 20)), draw(real(-math.pi, math.pi))]
        mu = list(pose)
        for _ in range(known):
            d, a = draw(real(2.0, 15.0)), draw(real(-math.pi, math.pi))
            mu += [pose[0] + d * math.cos(a), pose[1] + d * math.sin(a)]
        n = len(mu)
        sxy, sth = draw(real(0.05, 0.5)), draw(real(0.01, 0.2))
        d = np.empty(n)
        d[:3] = [sxy**2, sxy**2, sth**2]
        d[3:] = rng.uniform(0.05, 0.5, n - 3) ** 2
        a = np.eye(n)
        for k in range(3, n, 2):
            arm = np.asarray(mu[k : k + 2]) - np.asarray(pose[:2])
            a[k : k + 2, :3] = rng.uniform(0, 1) * np.array([[1, 0, -arm[1]], [0, 1, arm[0]]])
        sigma = a @ np.diag(d) @ a.T
        u = [draw(real(-math.pi, math.pi)), draw(real(0.0, 3.0)), draw(real(-math.pi, math.pi))]
        motion = np.diag([draw(real(1e-4, 0.01)), draw(real(1e-4, 0.05)), draw(real(1e-4, 0.01))])
        predicted = _ekf.odometry_step(pose, u)
        truth = np.asarray(predicted) + rng.normal(size=3) * [0.1, 0.1, 0.03]
        sr, sb = draw(real(0.05, 0.3)), draw(real(0.005, 0.03))
        rho = draw(real(-0.5, 0.5))
        r = np.array([[sr * sr, rho * sr * sb], [rho * sr * sb, sb * sb]])
        count = draw(st.integers(1, 3))
        new = draw(st.integers(0, min(2, count)))
        order = draw(st.permutations(list(range(known))))[: count - new]
        ids = [int(j) for j in order] + [known + k for k in range(new)]
        ids = draw(st.permutations(ids))
        # new landmarks take the ids known, known + 1, ... in the order they first appear
        renumber = iter(range(known, known + new))
        ids = [j if j < known else next(renumber) for j in ids]
        z = []
        for j in ids:
            if j < known:
                spot = np.asarray(mu[3 + 2 * j : 5 + 2 * j]) + rng.normal(size=2) * 0.05
            else:
                dist, ang = rng.uniform(2.0, 15.0), rng.uniform(-math.pi, math.pi)
                spot = truth[:2] + dist * np.array([math.cos(ang), math.sin(ang)])
            h = ekfslam.observe(truth, spot) + np.linalg.cholesky(r) @ rng.normal(size=2)
            z.append([float(h[0]), _wrap(float(h[1]))])
        return {
            "mu": [float(v) for v in mu],
            "Sigma": sigma.tolist(),
            "u": u,
            "M": motion.tolist(),
            "z": z,
            "ids": ids,
            "R": r.tolist(),
        }

    return draw()


def ekf_step_valid(
    mu: ArrayLike,
    Sigma: ArrayLike,
    u: Sequence[float],
    M: ArrayLike,
    z: ArrayLike,
    ids: Sequence[int],
    R: ArrayLike,
) -> bool:
    """``ekf_slam_step``'s domain: 1–3 mapped landmarks, ``Sigma``, ``M``, ``R`` symmetric
    positive definite, turns in [−π, π] and a drive of 0–3 m, 1–3 measurements (range
    0.5–30 m, bearing in [−π, π]) with distinct whole-number ids, each a mapped landmark or
    the next new one; every landmark at least 0.5 m from the robot whenever it is measured."""
    try:
        m = np.asarray(mu, dtype=float)
        zs = np.asarray(z, dtype=float)
        uu = [float(v) for v in u]
    except (TypeError, ValueError):
        return False
    if m.ndim != 1 or m.size not in (5, 7, 9) or len(uu) != 3:
        return False
    if abs(uu[0]) > math.pi or abs(uu[2]) > math.pi or not 0 <= uu[1] <= 3:
        return False
    if zs.ndim != 2 or zs.shape[1] != 2 or not 1 <= zs.shape[0] <= 3 or len(ids) != len(zs):
        return False
    if np.any(zs[:, 0] < 0.5) or np.any(zs[:, 0] > 30) or np.any(np.abs(zs[:, 1]) > math.pi):
        return False
    if any(isinstance(j, float) and not float(j).is_integer() for j in ids):
        return False
    known = (m.size - 3) // 2
    seen: set[int] = set()
    nxt = known
    for j in (int(v) for v in ids):
        if j in seen or j < 0 or j > nxt:
            return False
        seen.add(j)
        nxt += j == nxt
    if not all(_positive_definite(a, k) for a, k in ((Sigma, m.size), (M, 3), (R, 2))):
        return False
    state, _ = slam_predict(m, Sigma, uu, M)
    for zk, j in zip(zs, ids, strict=True):
        j = int(j)
        if 3 + 2 * j < state.size:
            if math.dist(state[:2], state[3 + 2 * j : 5 + 2 * j]) < 0.5:
                return False
        state = np.concatenate([state, ekfslam.inverse_observation(state[:3], zk)])
    out = ekf_slam_step(m, Sigma, uu, M, zs, ids, R)
    return bool(np.all(np.isfinite(out)) and abs(abs(out[0, 2]) - math.pi) > 1e-9)
