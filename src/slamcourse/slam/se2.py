"""Rigid motions of the plane, SE(2): poses ``(x, y, θ)`` and how they combine.

A pose ``(x, y, θ)`` (metres, metres, radians counter-clockwise from the world's x axis) is also
the motion that carries the world frame onto the robot's frame. Written as the homogeneous
matrix

    T = [[cos θ, −sin θ, x],
         [sin θ,  cos θ, y],
         [0,      0,     1]]

composition is the matrix product and the inverse the matrix inverse. Angles returned here are
wrapped into (−π, π].
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

Pose = tuple[float, float, float]


def wrap_angle(angle: float) -> float:
    """The same direction as ``angle`` (radians), as the unique value in (−π, π]."""
    wrapped = math.remainder(angle, 2 * math.pi)  # exact, in [−π, π]
    return math.pi if wrapped == -math.pi else wrapped


def rotation(theta: float) -> NDArray[np.float64]:
    """The 2×2 rotation by ``theta`` radians."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def compose(a: Sequence[float], b: Sequence[float]) -> Pose:
    """``a ⊕ b``: first move by ``a``, then by ``b`` expressed in ``a``'s frame."""
    xa, ya, ta = (float(v) for v in a)
    xb, yb, tb = (float(v) for v in b)
    c, s = math.cos(ta), math.sin(ta)
    return (xa + c * xb - s * yb, ya + s * xb + c * yb, wrap_angle(ta + tb))


def inverse(a: Sequence[float]) -> Pose:
    """``a⁻¹``: the motion that undoes ``a`` (``a ⊕ a⁻¹ = a⁻¹ ⊕ a = (0, 0, 0)``)."""
    x, y, t = (float(v) for v in a)
    c, s = math.cos(t), math.sin(t)
    return (-c * x - s * y, s * x - c * y, wrap_angle(-t))


def between(a: Sequence[float], b: Sequence[float]) -> Pose:
    """``a⁻¹ ⊕ b``: pose ``b`` seen from pose ``a`` (what odometry from ``a`` to ``b`` measures)."""
    return compose(inverse(a), b)


def to_matrix(pose: Sequence[float]) -> NDArray[np.float64]:
    """The 3×3 homogeneous matrix of ``pose`` (often called v2t)."""
    x, y, t = (float(v) for v in pose)
    matrix = np.eye(3)
    matrix[:2, :2] = rotation(t)
    matrix[:2, 2] = (x, y)
    return matrix


def from_matrix(matrix: NDArray[np.float64]) -> Pose:
    """The pose of a 3×3 homogeneous matrix (often called t2v); the angle in (−π, π]."""
    m = np.asarray(matrix, dtype=float)
    return (float(m[0, 2]), float(m[1, 2]), wrap_angle(math.atan2(m[1, 0], m[0, 0])))
