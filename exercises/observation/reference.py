"""Reference answers for chapter ``observation``: the range-bearing observation model.

A robot at pose ``(x_r, y_r, θ_r)`` (metres, metres, radians; heading counter-clockwise from the
world x axis) observes landmark ``j`` at ``(x_j, y_j)`` (metres). With

    Δx = x_j − x_r,   Δy = y_j − y_r,   q = Δx² + Δy²

the predicted measurement is

    h = [r, φ] = [√q, atan2(Δy, Δx) − θ_r]

range ``r`` in metres, bearing ``φ`` in radians (positive to the robot's left), wrapped into
(−π, π]. Every function takes the exercise's parameters as keyword arguments. Functions whose
name starts with ``mistake_`` compute the wrong answer of a named misconception.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

# Layout of the 2D EKF-SLAM state: the pose, then two numbers per landmark.
POSE_DIM = 3
LANDMARK_DIM = 2

# Sample points of an expression exercise: one array entry per point.
Samples = NDArray[np.float64]


def wrap_angle(angle: float) -> float:
    """The same angle (radians) wrapped into (−π, π]."""
    wrapped = math.remainder(angle, 2 * math.pi)  # in [−π, π]
    return math.pi if wrapped == -math.pi else wrapped


def predict_measurement(pose: Sequence[float], landmark: Sequence[float]) -> NDArray[np.float64]:
    """``h = [r, φ]`` for ``pose = (x_r, y_r, θ_r)`` and ``landmark = (x_j, y_j)``; shape (2,)."""
    xr, yr, thr = pose
    xj, yj = landmark
    dx, dy = xj - xr, yj - yr
    r = math.hypot(dx, dy)
    phi = wrap_angle(math.atan2(dy, dx) - thr)
    return np.array([r, phi])


def predicted_range(xr: float, yr: float, thr: float, xj: float, yj: float) -> float:
    """Predicted range ``r = √(Δx² + Δy²)`` in metres (the heading ``thr`` plays no part)."""
    return float(predict_measurement((xr, yr, thr), (xj, yj))[0])


def predicted_bearing(xr: float, yr: float, thr: float, xj: float, yj: float) -> float:
    """Predicted bearing ``φ = atan2(Δy, Δx) − θ_r`` in radians, wrapped into (−π, π]."""
    return float(predict_measurement((xr, yr, thr), (xj, yj))[1])


def innovation(z_r: float, z_b: float, h_r: float, h_b: float) -> list[float]:
    """Innovation ``ν = z − h`` (measured minus predicted): [metres, radians], shape (2,).

    The bearing difference is wrapped into (−π, π]: 3.1 rad and −3.1 rad are 0.08 rad apart.
    """
    return [z_r - h_r, wrap_angle(z_b - h_b)]


def observation_jacobian(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """Jacobian of ``h = [r, φ]`` with respect to ``(x_r, y_r, θ_r, x_j, y_j)``; shape (2, 5).

    Row 0 is ``∂r/∂·`` (dimensionless, m/rad for θ_r), row 1 ``∂φ/∂·`` (rad/m, rad/rad).
    """
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    return [
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
        [dy / q, -dx / q, -1.0, -dy / q, dx / q],
    ]


def observe_from_state(state: ArrayLike, landmark: int) -> NDArray[np.float64]:
    """``h(x)`` for the full state ``x = [x_r, y_r, θ_r, x_1, y_1, …]``, landmark ``landmark``
    (1-based) observed; shape (2,)."""
    x = np.asarray(state, dtype=float)
    start = POSE_DIM + LANDMARK_DIM * (landmark - 1)
    return predict_measurement(x[:POSE_DIM], x[start : start + LANDMARK_DIM])


def numeric_state_jacobian(
    state: ArrayLike, landmark: int, step: float = 1e-6
) -> NDArray[np.float64]:
    """Central-difference Jacobian ``H = ∂h/∂x`` of :func:`observe_from_state`; shape (2, n)."""
    x = np.asarray(state, dtype=float)
    H = np.zeros((2, x.size))
    for k in range(x.size):
        e = np.zeros_like(x)
        e[k] = step
        diff = observe_from_state(x + e, landmark) - observe_from_state(x - e, landmark)
        diff[1] = wrap_angle(diff[1])
        H[:, k] = diff / (2 * step)
    return H


def example_state(num_landmarks: int) -> NDArray[np.float64]:
    """A generic 2D state: the robot at (2, 3, π/4) and landmarks spread around it."""
    pose = [2.0, 3.0, math.pi / 4]
    landmarks = [
        (2.0 + 4.0 * math.cos(1.3 * k + 0.4), 3.0 + (3.0 + 0.5 * k) * math.sin(1.3 * k + 0.4))
        for k in range(num_landmarks)
    ]
    return np.array(pose + [c for point in landmarks for c in point])


def nonzero_jacobian_columns(observed: int, num_landmarks: int) -> list[str]:
    """Ids ``c1 … cn`` of the columns of ``H`` that are not identically zero when landmark
    ``observed`` (1-based) is measured, found from a numeric Jacobian at a generic state."""
    H = numeric_state_jacobian(example_state(num_landmarks), observed)
    return [f"c{k + 1}" for k in range(H.shape[1]) if np.any(np.abs(H[:, k]) > 1e-6)]


def d_range_d_xr(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``∂r/∂x_r = −Δx/√q`` (dimensionless), elementwise over sample arrays."""
    return -dx / np.sqrt(q)


def d_bearing_d_xr(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``∂φ/∂x_r = Δy/q`` (rad/m), elementwise over sample arrays."""
    return dy / q


# --- misconceptions -------------------------------------------------------------------------


def mistake_range_without_sqrt(xr: float, yr: float, thr: float, xj: float, yj: float) -> float:
    """``Δx² + Δy²``: the squared distance given as the range."""
    return (xj - xr) ** 2 + (yj - yr) ** 2


def mistake_bearing_in_degrees(xr: float, yr: float, thr: float, xj: float, yj: float) -> float:
    """The right bearing, but written in degrees."""
    return math.degrees(predicted_bearing(xr, yr, thr, xj, yj))


def mistake_bearing_heading_ignored(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> float:
    """``atan2(Δy, Δx)``: the world-frame direction, the heading not subtracted."""
    return math.atan2(yj - yr, xj - xr)


def mistake_bearing_heading_added(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> float:
    """``atan2(Δy, Δx) + θ_r``: the heading added instead of subtracted (a sign slip)."""
    return math.atan2(yj - yr, xj - xr) + thr


def mistake_innovation_reversed(z_r: float, z_b: float, h_r: float, h_b: float) -> list[float]:
    """``h − z``: predicted minus measured, the sign of the innovation flipped."""
    return [-v for v in innovation(z_r, z_b, h_r, h_b)]


def mistake_jacobian_heading_term_dropped(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """The Jacobian with ``∂φ/∂θ_r = 0`` instead of −1."""
    H = observation_jacobian(xr, yr, thr, xj, yj)
    H[1][2] = 0.0
    return H


def mistake_jacobian_bearing_signs_flipped(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """The Jacobian with the signs of the bearing row's position entries flipped."""
    H = observation_jacobian(xr, yr, thr, xj, yj)
    H[1] = [-H[1][0], -H[1][1], H[1][2], -H[1][3], -H[1][4]]
    return H


def mistake_jacobian_range_over_q(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """The Jacobian with the range row divided by ``q`` instead of ``√q``."""
    H = observation_jacobian(xr, yr, thr, xj, yj)
    q = (xj - xr) ** 2 + (yj - yr) ** 2
    H[0] = [-(xj - xr) / q, -(yj - yr) / q, 0.0, (xj - xr) / q, (yj - yr) / q]
    return H


def mistake_d_range_sign_flipped(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``+Δx/√q``: that is ``∂r/∂x_j``, the landmark's derivative."""
    return dx / np.sqrt(q)


def mistake_d_range_without_sqrt(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``−Δx/q``: the square root dropped from the denominator."""
    return -dx / q


def mistake_d_range_wrong_coordinate(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``−Δy/√q``: that is ``∂r/∂y_r``."""
    return -dy / np.sqrt(q)


def mistake_d_bearing_sign_flipped(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``−Δy/q``: that is ``∂φ/∂x_j``, the landmark's derivative."""
    return -dy / q


def mistake_d_bearing_wrong_coordinate(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``−Δx/q``: that is ``∂φ/∂y_r``."""
    return -dx / q


def mistake_d_bearing_over_range(dx: Samples, dy: Samples, q: Samples) -> Samples:
    """``Δy/√q``: the range's denominator carried over to the bearing."""
    return dy / np.sqrt(q)


# --- code exercises ``observation/observation-model`` and ``observation/jacobian`` ----------

# Step of the central differences in :func:`range_bearing_jacobian` (metres, radians). With
# coordinates of tens of metres and ranges above 0.5 m, the truncation error (~h²/r³) and the
# rounding error (~1e-16·r/h) both stay near 1e-9, far inside the exercise's tolerance.
FD_STEP = 1e-5


def observation_model(xr: float, yr: float, thr: float, xj: float, yj: float) -> list[float]:
    """``[r, φ]``: range (metres) and bearing (radians, wrapped into (−π, π]) of landmark
    ``(xj, yj)`` seen from the pose ``(xr, yr, thr)``."""
    return [float(v) for v in predict_measurement((xr, yr, thr), (xj, yj))]


def range_bearing_jacobian(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> NDArray[np.float64]:
    """``∂[r, φ]/∂(x_r, y_r, θ_r, x_j, y_j)`` by central finite differences; shape (2, 5).

    Each column nudges one of the five inputs by ±``FD_STEP``; the bearing difference is wrapped
    so that a bearing near ±π does not produce a jump of 2π.
    """
    point = np.array([xr, yr, thr, xj, yj], dtype=float)
    J = np.zeros((2, 5))
    for k in range(5):
        e = np.zeros(5)
        e[k] = FD_STEP
        plus = np.array(observation_model(*(point + e)))
        minus = np.array(observation_model(*(point - e)))
        diff = plus - minus
        diff[1] = wrap_angle(diff[1])
        J[:, k] = diff / (2 * FD_STEP)
    return J


def observation_model_degrees(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[float]:
    """Wrong: the bearing ``atan2(Δy, Δx) − θ_r`` (not wrapped) converted to degrees."""
    dx, dy = xj - xr, yj - yr
    return [math.hypot(dx, dy), math.degrees(math.atan2(dy, dx) - thr)]


def observation_model_heading_ignored(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[float]:
    """Wrong: the world-frame direction ``atan2(Δy, Δx)``, the heading not subtracted."""
    return [math.hypot(xj - xr, yj - yr), math.atan2(yj - yr, xj - xr)]


def observation_model_atan(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[float]:
    """Wrong: ``atan(Δy/Δx) − θ_r``, which folds landmarks behind the robot onto the front.

    (A learner's version divides by zero when ``Δx = 0``; this one returns ±π/2 there, the limit
    ``atan`` approaches, so that it can be recognised on every input.)
    """
    dx, dy = xj - xr, yj - yr
    world = math.atan(dy / dx) if dx != 0 else math.copysign(math.pi / 2, dy)
    return [math.hypot(dx, dy), world - thr]


def observation_model_squared_range(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[float]:
    """Wrong: ``Δx² + Δy²`` (m²) returned as the range."""
    r, phi = observation_model(xr, yr, thr, xj, yj)
    return [r * r, phi]


def jacobian_landmark_signs_flipped(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """Wrong: the landmark columns with the pose columns' signs (``∂Δx/∂x_j`` taken as −1)."""
    H = observation_jacobian(xr, yr, thr, xj, yj)
    for row in H:
        row[3], row[4] = row[0], row[1]
    return H


def jacobian_heading_plus_one(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """Wrong: ``∂φ/∂θ_r = +1`` (the heading enters φ with a minus sign)."""
    H = observation_jacobian(xr, yr, thr, xj, yj)
    H[1][2] = 1.0
    return H


def jacobian_range_without_sqrt(
    xr: float, yr: float, thr: float, xj: float, yj: float
) -> list[list[float]]:
    """Wrong: the range row divided by ``q`` instead of ``√q`` (e.g. ``−Δx/q``)."""
    return mistake_jacobian_range_over_q(xr, yr, thr, xj, yj)


# --- the domains the prompts state (``valid:`` of the code exercises) -------------------------


def _in_map(xr: float, yr: float, thr: float, xj: float, yj: float) -> bool:
    return all(abs(v) <= 200 for v in (xr, yr, xj, yj)) and abs(thr) <= 10


def landmark_clear_of_robot(xr: float, yr: float, thr: float, xj: float, yj: float) -> bool:
    """``observation_model``'s domain: the map and headings of the prompt, and the landmark at
    least 0.1 m from the robot."""
    return _in_map(xr, yr, thr, xj, yj) and math.hypot(xj - xr, yj - yr) >= 0.1


def landmark_half_metre_away(xr: float, yr: float, thr: float, xj: float, yj: float) -> bool:
    """``range_bearing_jacobian``'s domain: as the model's, the landmark at least 0.5 m away."""
    return _in_map(xr, yr, thr, xj, yj) and math.hypot(xj - xr, yj - yr) >= 0.5
