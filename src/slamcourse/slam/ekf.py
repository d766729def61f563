"""The odometry motion model of a planar robot and the EKF's prediction step.

A motion ``u = (δrot1, δtrans, δrot2)`` turns the robot by ``δrot1``, drives it ``δtrans``
metres straight ahead, then turns it by ``δrot2`` (radians). From the pose ``(x, y, θ)``:

    x' = x + δtrans·cos(θ + δrot1)
    y' = y + δtrans·sin(θ + δrot1)
    θ' = θ + δrot1 + δrot2

The EKF propagates the mean through this model and the covariance through its Jacobians:
``Σ' = G Σ Gᵀ + V M Vᵀ`` with ``G = ∂x'/∂x`` (3×3), ``V = ∂x'/∂u`` (3×3) and ``M`` the 3×3
covariance of the motion's noise.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

from slamcourse.slam.se2 import Pose, wrap_angle


def odometry_step(pose: Sequence[float], u: Sequence[float]) -> Pose:
    """The pose after the motion ``u = (δrot1, δtrans, δrot2)``; heading wrapped to (−π, π]."""
    x, y, theta = (float(v) for v in pose)
    rot1, trans, rot2 = (float(v) for v in u)
    heading = theta + rot1
    return (
        x + trans * math.cos(heading),
        y + trans * math.sin(heading),
        wrap_angle(theta + rot1 + rot2),
    )


def jacobian_state(pose: Sequence[float], u: Sequence[float]) -> NDArray[np.float64]:
    """``G = ∂x'/∂(x, y, θ)``, shape (3, 3)."""
    theta = float(pose[2])
    rot1, trans = float(u[0]), float(u[1])
    c, s = math.cos(theta + rot1), math.sin(theta + rot1)
    return np.array([[1.0, 0.0, -trans * s], [0.0, 1.0, trans * c], [0.0, 0.0, 1.0]])


def jacobian_control(pose: Sequence[float], u: Sequence[float]) -> NDArray[np.float64]:
    """``V = ∂x'/∂(δrot1, δtrans, δrot2)``, shape (3, 3)."""
    theta = float(pose[2])
    rot1, trans = float(u[0]), float(u[1])
    c, s = math.cos(theta + rot1), math.sin(theta + rot1)
    return np.array([[-trans * s, c, 0.0], [trans * c, s, 0.0], [1.0, 0.0, 1.0]])


def predict(
    mean: Sequence[float], cov: ArrayLike, u: Sequence[float], motion_cov: ArrayLike
) -> tuple[Pose, NDArray[np.float64]]:
    """One EKF prediction: the new mean and ``Σ' = G Σ Gᵀ + V M Vᵀ`` (3×3)."""
    sigma = np.asarray(cov, dtype=float)
    m = np.asarray(motion_cov, dtype=float)
    g = jacobian_state(mean, u)
    v = jacobian_control(mean, u)
    return odometry_step(mean, u), g @ sigma @ g.T + v @ m @ v.T


def numerical_jacobian(
    f: Callable[[NDArray[np.float64]], ArrayLike],
    x: Sequence[float],
    step: float = 1e-6,
    angle_rows: Sequence[int] = (2,),
) -> NDArray[np.float64]:
    """Central finite differences of ``f`` (a function of a vector) at ``x``.

    Rows listed in ``angle_rows`` are differenced modulo 2π, so a jump of the wrapped output
    across ±π does not show up as a huge slope.
    """
    point = np.asarray(x, dtype=float)
    columns = []
    for k in range(point.size):
        dx = np.zeros_like(point)
        dx[k] = step
        hi = np.asarray(f(point + dx), dtype=float)
        lo = np.asarray(f(point - dx), dtype=float)
        diff = hi - lo
        for r in angle_rows:
            diff[r] = wrap_angle(float(diff[r]))
        columns.append(diff / (2 * step))
    return np.stack(columns, axis=1)
