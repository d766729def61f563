"""Reference answers for chapter ``motion``: the odometry motion model and the EKF prediction.

A motion ``u = (δrot1, δtrans, δrot2)`` (radians, metres, radians) turns the robot by
``δrot1``, drives ``δtrans`` straight ahead and turns by ``δrot2``. The mathematics lives in
:mod:`slamcourse.slam.ekf`: ``odometry_step`` for the mean, ``jacobian_state`` (``G``) and
``jacobian_control`` (``V``) for the covariance ``Σ' = G Σ Gᵀ + V M Vᵀ``. Functions whose name
starts with ``mistake_`` compute the answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam import ekf
from slamcourse.slam.se2 import wrap_angle

Samples = NDArray[np.float64]
Matrix = NDArray[np.float64]


# --- numeric exercises ------------------------------------------------------------------------


def step_value(x: float, y: float, t: float, rot1: float, trans: float, rot2: float) -> list[float]:
    return list(ekf.odometry_step((x, y, t), (rot1, trans, rot2)))


def mistake_step_rot1_ignored(
    x: float, y: float, t: float, rot1: float, trans: float, rot2: float
) -> list[float]:
    """Drives along the old heading θ, as if the first turn came after the translation."""
    return [x + trans * math.cos(t), y + trans * math.sin(t), wrap_angle(t + rot1 + rot2)]


def mistake_step_full_turn_first(
    x: float, y: float, t: float, rot1: float, trans: float, rot2: float
) -> list[float]:
    """Drives along θ + δrot1 + δrot2, as if both turns came before the translation."""
    h = t + rot1 + rot2
    return [x + trans * math.cos(h), y + trans * math.sin(h), wrap_angle(h)]


def d_x_d_theta(trans: Samples, theta: Samples, rot1: Samples) -> Samples:
    """``∂x'/∂θ = −δtrans·sin(θ + δrot1)``."""
    return -trans * np.sin(theta + rot1)


def mistake_d_x_d_theta_rot1_dropped(trans: Samples, theta: Samples, rot1: Samples) -> Samples:
    return -trans * np.sin(theta)


def mistake_d_x_d_theta_sign(trans: Samples, theta: Samples, rot1: Samples) -> Samples:
    return trans * np.sin(theta + rot1)


def mistake_d_x_d_theta_trans_dropped(trans: Samples, theta: Samples, rot1: Samples) -> Samples:
    return -np.sin(theta + rot1)


def lateral_variance(trans: float, var_y: float, var_t: float, var_rot1: float) -> float:
    """``Σ'_yy`` after driving ``trans`` along +x from heading 0, with δrot1 = δrot2 = 0.

    ``Σ = diag(var_x, var_y, var_t)`` and ``M = diag(var_rot1, var_trans, var_rot2)``; only the
    entries that reach ``y`` matter: ``Σ'_yy = var_y + trans²·var_t + trans²·var_rot1``.
    """
    sigma = np.diag([0.01, var_y, var_t])
    m = np.diag([var_rot1, 0.02, 0.001])
    _, cov = ekf.predict((0.0, 0.0, 0.0), sigma, (0.0, trans, 0.0), m)
    return float(cov[1, 1])


def mistake_lateral_no_state_jacobian(
    trans: float, var_y: float, var_t: float, var_rot1: float
) -> float:
    """``Σ + V M Vᵀ``: the heading's uncertainty is not carried into the position."""
    return var_y + trans**2 * var_rot1


def mistake_lateral_no_motion_noise(
    trans: float, var_y: float, var_t: float, var_rot1: float
) -> float:
    """``G Σ Gᵀ`` only: the motion itself adds no uncertainty."""
    return var_y + trans**2 * var_t


def mistake_lateral_not_squared(trans: float, var_y: float, var_t: float, var_rot1: float) -> float:
    """Variances scaled by the distance instead of its square."""
    return var_y + trans * var_t + trans * var_rot1


# --- code: odometry_step ----------------------------------------------------------------------


def odometry_step(pose: Sequence[float], u: Sequence[float]) -> list[float]:
    return list(ekf.odometry_step(pose, u))


def _coord() -> Any:
    from hypothesis import strategies as st

    return st.floats(-20.0, 20.0, allow_nan=False, allow_infinity=False)


def _pose() -> Any:
    from hypothesis import strategies as st

    angle = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    return st.tuples(_coord(), _coord(), angle)


def _motion() -> Any:
    from hypothesis import strategies as st

    turn = st.floats(-math.pi, math.pi, allow_nan=False, allow_infinity=False)
    trans = st.floats(0.0, 5.0, allow_nan=False, allow_infinity=False)
    return st.tuples(turn, trans, turn)


def step_inputs() -> Any:
    """A pose (metres, radians in [−π, π]) and a motion (turns in [−π, π], 0–5 m)."""
    from hypothesis import strategies as st

    return st.fixed_dictionaries({"pose": _pose(), "u": _motion()})


def mistake_odometry_rot1_ignored(pose: Sequence[float], u: Sequence[float]) -> list[float]:
    return mistake_step_rot1_ignored(*pose, *u)


def mistake_odometry_rot2_forgotten(pose: Sequence[float], u: Sequence[float]) -> list[float]:
    """The final heading misses the second turn."""
    x, y, t = pose
    rot1, trans, _ = u
    return [x + trans * math.cos(t + rot1), y + trans * math.sin(t + rot1), wrap_angle(t + rot1)]


def mistake_odometry_sin_cos_swapped(pose: Sequence[float], u: Sequence[float]) -> list[float]:
    x, y, t = pose
    rot1, trans, rot2 = u
    h = t + rot1
    return [x + trans * math.sin(h), y + trans * math.cos(h), wrap_angle(t + rot1 + rot2)]


# --- code: predict_covariance -----------------------------------------------------------------


def predict_covariance(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> Matrix:
    return ekf.predict(pose, sigma, u, motion_cov)[1]


def _spd(scale: float) -> Any:
    """A random symmetric positive-definite 3×3 matrix ``L Lᵀ`` with entries around ``scale``."""
    from hypothesis import strategies as st

    diag = st.floats(0.05, 1.0, allow_nan=False, allow_infinity=False)
    off = st.floats(-0.5, 0.5, allow_nan=False, allow_infinity=False)

    def build(d: list[float], o: list[float]) -> list[list[float]]:
        low = np.array([[d[0], 0, 0], [o[0], d[1], 0], [o[1], o[2], d[2]]]) * math.sqrt(scale)
        return (low @ low.T).tolist()  # type: ignore[no-any-return]

    return st.builds(
        build, st.lists(diag, min_size=3, max_size=3), st.lists(off, min_size=3, max_size=3)
    )


def covariance_inputs() -> Any:
    """Pose, motion, a state covariance (variances up to ~1) and a motion-noise covariance."""
    from hypothesis import strategies as st

    return st.fixed_dictionaries(
        {"pose": _pose(), "u": _motion(), "sigma": _spd(1.0), "motion_cov": _spd(0.1)}
    )


def _g_v(pose: Sequence[float], u: Sequence[float]) -> tuple[Matrix, Matrix]:
    return ekf.jacobian_state(pose, u), ekf.jacobian_control(pose, u)


def mistake_cov_no_motion_noise(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> Matrix:
    g, _ = _g_v(pose, u)
    return g @ np.asarray(sigma) @ g.T


def mistake_cov_noise_not_mapped(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> Matrix:
    """``G Σ Gᵀ + M``: the noise of (δrot1, δtrans, δrot2) added as if it were noise of (x, y, θ)."""
    g, _ = _g_v(pose, u)
    return g @ np.asarray(sigma) @ g.T + np.asarray(motion_cov)


def mistake_cov_heading_without_rot1(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> Matrix:
    """Jacobians evaluated at heading θ instead of θ + δrot1."""
    g, v = _g_v((pose[0], pose[1], pose[2] - u[0]), u)
    return g @ np.asarray(sigma) @ g.T + v @ np.asarray(motion_cov) @ v.T


def mistake_cov_transposed(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> Matrix:
    """``Gᵀ Σ G + Vᵀ M V``."""
    g, v = _g_v(pose, u)
    return g.T @ np.asarray(sigma) @ g + v.T @ np.asarray(motion_cov) @ v


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def step_valid(pose: Sequence[float], u: Sequence[float]) -> bool:
    """``odometry_step``'s domain: positions in [−20, 20] m, a heading in [−π, π], turns in
    [−π, π] and a translation in [0, 5] m."""
    if len(pose) != 3 or len(u) != 3:
        return False
    x, y, t = (float(v) for v in pose)
    rot1, trans, rot2 = (float(v) for v in u)
    return (
        abs(x) <= 20 and abs(y) <= 20 and abs(t) <= math.pi
        and abs(rot1) <= math.pi and abs(rot2) <= math.pi and 0 <= trans <= 5
    )


def _positive_definite(m: ArrayLike, n: int) -> bool:
    """A symmetric positive-definite ``n × n`` matrix of finite numbers."""
    a = np.asarray(m, dtype=float)
    if a.shape != (n, n) or not np.all(np.isfinite(a)) or not np.allclose(a, a.T, atol=1e-12):
        return False
    try:
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        return False
    return True


def covariance_valid(
    pose: Sequence[float], u: Sequence[float], sigma: ArrayLike, motion_cov: ArrayLike
) -> bool:
    """``predict_covariance``'s domain: a pose and odometry as for ``odometry_step`` (any
    position), and two symmetric positive-definite 3×3 covariances."""
    if len(pose) != 3 or len(u) != 3 or float(u[1]) < 0:
        return False
    return _positive_definite(sigma, 3) and _positive_definite(motion_cov, 3)
