"""Closed-form rigid alignment of 2-D point sets and one ICP iteration: chapter 18.

Points are rows of ``(N, 2)`` arrays in metres. ``align_2d(P, Q)`` finds the rotation ``R``
(``det R = +1``) and translation ``t`` minimising ``Σ_i ‖R p_i + t − q_i‖²`` for known
correspondences ``p_i ↔ q_i`` (Kabsch–Umeyama without scale). In 2-D the optimal angle has a
closed form: with centred points ``p'``, ``q'``, ``θ = atan2(Σ p' × q', Σ p' · q')``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

Matrix = NDArray[np.float64]


def rotation(theta: float) -> Matrix:
    """The 2×2 rotation by ``theta`` radians (counter-clockwise)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, -s], [s, c]])


def cross_covariance(p: ArrayLike, q: ArrayLike) -> tuple[Matrix, Matrix, Matrix]:
    """Centroids ``p̄``, ``q̄`` (shape (2,)) and ``H = Σ (p_i − p̄)(q_i − q̄)ᵀ`` (2×2)."""
    pa, qa = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    pm, qm = pa.mean(axis=0), qa.mean(axis=0)
    return pm, qm, (pa - pm).T @ (qa - qm)


def align_svd(p: ArrayLike, q: ArrayLike) -> tuple[Matrix, Matrix]:
    """``(R, t)`` by the SVD of ``H = U S Vᵀ``: ``R = V diag(1, det(V Uᵀ)) Uᵀ``, ``t = q̄ − R p̄``.

    The ``det`` factor turns the best orthogonal matrix into the best *rotation* when the
    unconstrained optimum is a reflection.
    """
    pm, qm, h = cross_covariance(p, q)
    u, _, vt = np.linalg.svd(h)
    d = np.sign(np.linalg.det(vt.T @ u.T)) or 1.0
    r = vt.T @ np.diag([1.0, d]) @ u.T
    return r, qm - r @ pm


def align_angle(p: ArrayLike, q: ArrayLike) -> tuple[float, Matrix]:
    """``(θ, t)`` in closed form: ``θ = atan2(H₀₁ − H₁₀, H₀₀ + H₁₁)``, ``t = q̄ − R(θ) p̄``."""
    pm, qm, h = cross_covariance(p, q)
    theta = math.atan2(h[0, 1] - h[1, 0], h[0, 0] + h[1, 1])
    return theta, qm - rotation(theta) @ pm


def sum_squared_error(p: ArrayLike, q: ArrayLike, theta: float, t: ArrayLike) -> float:
    """``Σ ‖R(θ) p_i + t − q_i‖²`` in m²."""
    pa, qa = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    residual = pa @ rotation(theta).T + np.asarray(t, dtype=float) - qa
    return float(np.sum(residual**2))


def nearest_neighbours(p: ArrayLike, q: ArrayLike) -> NDArray[np.int64]:
    """For each row of ``p``, the index of the nearest row of ``q`` (ties: the smaller index)."""
    pa, qa = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    d2 = np.sum((pa[:, None, :] - qa[None, :, :]) ** 2, axis=2)
    return np.asarray(np.argmin(d2, axis=1), dtype=np.int64)


def icp_step(p: ArrayLike, q: ArrayLike) -> tuple[float, Matrix, NDArray[np.int64]]:
    """One ICP iteration: pair each ``p_i`` with its nearest ``q``, then align in closed form.

    Returns ``(θ, t, pairs)`` with ``pairs[i]`` the index in ``q`` matched to ``p_i``.
    """
    pairs = nearest_neighbours(p, q)
    theta, t = align_angle(p, np.asarray(q, dtype=float)[pairs])
    return theta, t, pairs
