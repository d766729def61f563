"""Two-view geometry and RANSAC: the mathematics of chapter 6 (visual odometry).

Image points are normalised homogeneous 3-vectors ``x = [u, v, 1]`` (pixel coordinates with the
camera intrinsics removed, ``x = K⁻¹ p``). When the second camera frame is reached from the first
by the rotation ``R`` (3 × 3) and the translation ``t`` (3,), the essential matrix is
``E = [t]× R`` and every correspondence ``x ↔ x′`` of one 3D point satisfies ``x′ᵀ E x = 0``.
In pixel coordinates the same constraint reads ``p′ᵀ F p = 0`` with the fundamental matrix
``F = K′⁻ᵀ E K⁻¹``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from statistics import NormalDist

import numpy as np
from numpy.typing import ArrayLike, NDArray

Array = NDArray[np.float64]

#: Degrees of freedom of E: 3 (rotation) + 3 (translation) − 1 (the unobservable scale).
ESSENTIAL_DOF = 5
#: Degrees of freedom of F: 9 entries − 1 (scale) − 1 (det F = 0).
FUNDAMENTAL_DOF = 7


def skew(t: ArrayLike) -> Array:
    """``[t]×`` (3 × 3): the matrix with ``[t]× v = t × v`` for every 3-vector ``v``."""
    tx, ty, tz = np.asarray(t, dtype=float).reshape(3)
    return np.array([[0.0, -tz, ty], [tz, 0.0, -tx], [-ty, tx, 0.0]])


def rotation_z(angle: float) -> Array:
    """Rotation (3 × 3) by ``angle`` radians about the z axis (the optical axis)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def rotation_y(angle: float) -> Array:
    """Rotation (3 × 3) by ``angle`` radians about the y axis (a camera panning left/right)."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def essential_from_pose(t: ArrayLike, R: ArrayLike) -> Array:
    """``E = [t]× R`` (3 × 3) for the translation ``t`` (3,) and rotation ``R`` (3 × 3)."""
    E: Array = skew(t) @ np.asarray(R, dtype=float)
    return E


def epipolar_residual(E: ArrayLike, x: ArrayLike, x2: ArrayLike) -> float:
    """``x′ᵀ E x``: ``x`` (3,) is the point in image 1, ``x2`` (3,) its match ``x′`` in image 2."""
    return float(
        np.asarray(x2, dtype=float) @ np.asarray(E, dtype=float) @ np.asarray(x, dtype=float)
    )


def singular_values(M: ArrayLike) -> Array:
    """Singular values of the 3 × 3 matrix ``M``, largest first (3,)."""
    return np.linalg.svd(np.asarray(M, dtype=float), compute_uv=False)


def is_essential(M: ArrayLike, rtol: float = 1e-6) -> bool:
    """The singular-value test: ``M`` is an essential matrix (up to scale) exactly when its
    singular values are ``(σ, σ, 0)`` with ``σ > 0``; tested relative to the largest one."""
    s1, s2, s3 = singular_values(M)
    return bool(s1 > 0 and abs(s1 - s2) <= rtol * s1 and abs(s3) <= rtol * s1)


def fundamental_from_essential(E: ArrayLike, K: ArrayLike, K2: ArrayLike | None = None) -> Array:
    """``F = K′⁻ᵀ E K⁻¹`` (3 × 3): the constraint ``x′ᵀ E x = 0`` rewritten for pixel coordinates
    ``p = K x`` (image 1, intrinsics ``K``) and ``p′ = K′ x′`` (image 2, ``K′``, default ``K``)."""
    K1 = np.asarray(K, dtype=float)
    K2m = K1 if K2 is None else np.asarray(K2, dtype=float)
    F: Array = np.linalg.inv(K2m).T @ np.asarray(E, dtype=float) @ np.linalg.inv(K1)
    return F


def essential_from_fundamental(F: ArrayLike, K: ArrayLike, K2: ArrayLike | None = None) -> Array:
    """``E = K′ᵀ F K`` (3 × 3), the inverse of :func:`fundamental_from_essential`."""
    K1 = np.asarray(K, dtype=float)
    K2m = K1 if K2 is None else np.asarray(K2, dtype=float)
    E: Array = K2m.T @ np.asarray(F, dtype=float) @ K1
    return E


def intrinsics(f: float, cx: float, cy: float) -> Array:
    """Camera matrix ``K`` (3 × 3) with focal length ``f`` and principal point ``(cx, cy)``,
    all in pixels, square pixels and no skew."""
    return np.array([[f, 0.0, cx], [0.0, f, cy], [0.0, 0.0, 1.0]])


# --- RANSAC ---------------------------------------------------------------------------------


def ransac_ratio(inlier_ratio: float, sample_size: int, confidence: float) -> float:
    """``log(1 − p) / log(1 − wˢ)``: the real number of samples before rounding up."""
    return math.log(1 - confidence) / math.log(1 - inlier_ratio**sample_size)


def ransac_iterations(inlier_ratio: float, sample_size: int, confidence: float) -> int:
    """Fewest RANSAC samples ``N = ⌈log(1 − p) / log(1 − wˢ)⌉`` such that, with probability at
    least ``p = confidence``, one sample of ``s = sample_size`` matches is all inliers when a
    fraction ``w = inlier_ratio`` of the matches are inliers."""
    return math.ceil(ransac_ratio(inlier_ratio, sample_size, confidence))


def all_samples_fail(inlier_ratio: float, sample_size: int, iterations: int) -> float:
    """``(1 − wˢ)ᴺ``: the probability that none of ``N`` samples is all inliers."""
    return float((1 - inlier_ratio**sample_size) ** iterations)


def chi2_quantile(confidence: float, dof: int) -> float:
    """The ``confidence`` quantile of the χ² distribution with ``dof`` = 1 or 2 degrees of freedom,
    in closed form: χ²₁ is the square of a standard normal, so its quantile is ``z²`` with
    ``z`` the ``(1 + p)/2`` normal quantile; χ²₂ is exponential with mean 2, ``−2 ln(1 − p)``."""
    if dof == 1:
        z = NormalDist().inv_cdf((1 + confidence) / 2)
        return z * z
    if dof == 2:
        return -2.0 * math.log(1 - confidence)
    raise ValueError(f"chi2_quantile: dof must be 1 or 2, got {dof}")


def sampson_threshold(sigma: float, confidence: float) -> float:
    """Threshold ``τ²`` (px²) on the squared Sampson distance of a correspondence with image
    noise ``sigma`` (px): the error of a true match is ``σ² χ²(1)``, so ``τ² = σ² χ²₁(p)``."""
    return sigma**2 * chi2_quantile(confidence, 1)


def scaled(direction: Sequence[float], scale: float) -> list[float]:
    """The translation ``scale · t̂`` (metres) from a unit direction ``t̂`` and a metric scale."""
    return [scale * c for c in direction]
