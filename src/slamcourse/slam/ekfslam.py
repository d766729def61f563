"""EKF-SLAM's update step and how a new landmark enters the state.

The state is ``μ = (x_r, y_r, θ_r, x_1, y_1, …, x_N, y_N)`` (metres and radians; ``n = 3 + 2N``
entries) with covariance ``P`` (``n × n``, symmetric positive semi-definite). A range-bearing
measurement ``z = (r, φ)`` (metres, radians; bearing counter-clockwise from the robot's heading)
has noise covariance ``R`` (2×2, m², m·rad, rad²).

Update with a measurement of landmark ``j`` predicted as ``h = h(μ)`` with Jacobian ``H``
(``2 × n``, nonzero only in the pose's and landmark ``j``'s columns):

    ν = z − h          (bearing entry wrapped into (−π, π])
    S = H P Hᵀ + R     (2×2)
    K = P Hᵀ S⁻¹       (n×2)
    μ⁺ = μ + K ν
    P⁺ = (I − K H) P (I − K H)ᵀ + K R Kᵀ     (Joseph form; equal to (I − K H) P for this K)

Initialising landmark ``N + 1`` from a measurement inverts the observation model:

    g(x_r, z) = (x_r + r cos(θ_r + φ), y_r + r sin(θ_r + φ))

and augments ``μ`` by ``g`` and ``P`` by the blocks ``G_r P_r·`` and ``G_r P_rr G_rᵀ + G_z R G_zᵀ``
with ``G_r = ∂g/∂(x_r, y_r, θ_r)`` (2×3) and ``G_z = ∂g/∂(r, φ)`` (2×2).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam.se2 import wrap_angle

Vector = NDArray[np.float64]
Matrix = NDArray[np.float64]
Values = Sequence[float] | NDArray[np.float64]  # a short vector: a list or an array

POSE_DIM = 3
LANDMARK_DIM = 2


# --- the observation model ------------------------------------------------------------------


def observe(pose: Values, landmark: Values) -> Vector:
    """``h = (r, φ)``: range (m) and bearing (rad, wrapped) of ``landmark`` seen from ``pose``."""
    x, y, theta = (float(v) for v in pose)
    dx, dy = float(landmark[0]) - x, float(landmark[1]) - y
    return np.array([math.hypot(dx, dy), wrap_angle(math.atan2(dy, dx) - theta)])


def observation_jacobian(state: Sequence[float] | Vector, j: int) -> Matrix:
    """``H = ∂h/∂μ`` (2 × n) of a measurement of landmark ``j`` (0-based) at the state ``μ``.

    Only columns 0–2 (the pose) and ``3 + 2j``, ``4 + 2j`` (landmark ``j``) are nonzero.
    """
    mu = np.asarray(state, dtype=float)
    x, y = mu[0], mu[1]
    k = POSE_DIM + LANDMARK_DIM * j
    dx, dy = mu[k] - x, mu[k + 1] - y
    q = dx * dx + dy * dy
    r = math.sqrt(q)
    h = np.zeros((2, mu.size))
    h[:, :POSE_DIM] = [[-dx / r, -dy / r, 0.0], [dy / q, -dx / q, -1.0]]
    h[:, k : k + 2] = [[dx / r, dy / r], [-dy / q, dx / q]]
    return h


def innovation(z: Values, h: Values) -> Vector:
    """``ν = z − h`` (2,), the bearing difference wrapped into (−π, π]."""
    nu: Vector = np.array([float(z[0]) - float(h[0]), wrap_angle(float(z[1]) - float(h[1]))])
    return nu


# --- the update -----------------------------------------------------------------------------


def innovation_covariance(p: ArrayLike, h: ArrayLike, r: ArrayLike) -> Matrix:
    """``S = H P Hᵀ + R`` (m × m)."""
    pm, hm = np.asarray(p, dtype=float), np.asarray(h, dtype=float)
    s: Matrix = hm @ pm @ hm.T + np.asarray(r, dtype=float)
    return s


def kalman_gain(p: ArrayLike, h: ArrayLike, r: ArrayLike) -> Matrix:
    """``K = P Hᵀ S⁻¹`` (n × m), computed by solving ``S Kᵀ = H P`` (S and P symmetric)."""
    pm, hm = np.asarray(p, dtype=float), np.asarray(h, dtype=float)
    s = innovation_covariance(pm, hm, r)
    return np.asarray(np.linalg.solve(s, hm @ pm).T, dtype=float)


def update_covariance(p: ArrayLike, h: ArrayLike, r: ArrayLike) -> Matrix:
    """``P⁺`` in Joseph form, ``(I − K H) P (I − K H)ᵀ + K R Kᵀ`` (n × n).

    For the optimal gain it equals the simple form ``(I − K H) P``, but stays symmetric and
    positive semi-definite under rounding (and for any gain, optimal or not).
    """
    pm, hm, rm = (np.asarray(a, dtype=float) for a in (p, h, r))
    k = kalman_gain(pm, hm, rm)
    a = np.eye(pm.shape[0]) - k @ hm
    return np.asarray(a @ pm @ a.T + k @ rm @ k.T, dtype=float)


def update_covariance_simple(p: ArrayLike, h: ArrayLike, r: ArrayLike) -> Matrix:
    """``P⁺ = (I − K H) P``: the short form (exact only for the optimal gain)."""
    pm, hm = np.asarray(p, dtype=float), np.asarray(h, dtype=float)
    k = kalman_gain(pm, hm, r)
    return np.asarray((np.eye(pm.shape[0]) - k @ hm) @ pm, dtype=float)


def update(
    mu: ArrayLike, p: ArrayLike, z: Sequence[float], h: Sequence[float], hj: ArrayLike, r: ArrayLike
) -> tuple[Vector, Matrix]:
    """One EKF update with the range-bearing measurement ``z`` predicted as ``h`` (Jacobian
    ``hj``, 2 × n): ``(μ⁺, P⁺)``; the robot's heading in ``μ⁺`` is wrapped into (−π, π]."""
    m = np.array(mu, dtype=float)
    k = kalman_gain(p, hj, r)
    m = m + k @ innovation(z, h)
    m[2] = wrap_angle(float(m[2]))
    return m, update_covariance(p, hj, r)


# --- a new landmark -------------------------------------------------------------------------


def inverse_observation(pose: Values, z: Values) -> Vector:
    """``g(x_r, z)``: the world position (m) of a landmark measured at ``z = (r, φ)``; (2,)."""
    x, y, theta = (float(v) for v in pose)
    r, phi = float(z[0]), float(z[1])
    return np.array([x + r * math.cos(theta + phi), y + r * math.sin(theta + phi)])


def inverse_jacobian_pose(pose: Values, z: Values) -> Matrix:
    """``G_r = ∂g/∂(x_r, y_r, θ_r)``, shape (2, 3)."""
    a = float(pose[2]) + float(z[1])
    r = float(z[0])
    return np.array([[1.0, 0.0, -r * math.sin(a)], [0.0, 1.0, r * math.cos(a)]])


def inverse_jacobian_measurement(pose: Values, z: Values) -> Matrix:
    """``G_z = ∂g/∂(r, φ)``, shape (2, 2)."""
    a = float(pose[2]) + float(z[1])
    r = float(z[0])
    c, s = math.cos(a), math.sin(a)
    return np.array([[c, -r * s], [s, r * c]])


def augment(mu: ArrayLike, p: ArrayLike, z: Sequence[float], r: ArrayLike) -> tuple[Vector, Matrix]:
    """The state and covariance with a new landmark initialised from ``z`` appended last.

    ``mu`` (n,), ``p`` (n, n), ``z = (r, φ)``, ``r`` the 2×2 measurement covariance. Returns
    ``μ'`` (n + 2,) and ``P'`` (n + 2, n + 2):

        P' = [[P,        (G_r P_r·)ᵀ               ],
              [G_r P_r·, G_r P_rr G_rᵀ + G_z R Gzᵀ]]

    where ``P_r·`` are the pose's three rows of ``P``.
    """
    m = np.asarray(mu, dtype=float)
    pm = np.asarray(p, dtype=float)
    rm = np.asarray(r, dtype=float)
    pose = [float(v) for v in m[:POSE_DIM]]
    g_r = inverse_jacobian_pose(pose, z)
    g_z = inverse_jacobian_measurement(pose, z)
    cross = g_r @ pm[:POSE_DIM, :]  # (2, n): the new landmark against every state entry
    new_block = g_r @ pm[:POSE_DIM, :POSE_DIM] @ g_r.T + g_z @ rm @ g_z.T
    n = m.size
    out = np.zeros((n + 2, n + 2))
    out[:n, :n] = pm
    out[n:, :n] = cross
    out[:n, n:] = cross.T
    out[n:, n:] = new_block
    return np.concatenate([m, inverse_observation(pose, z)]), out
