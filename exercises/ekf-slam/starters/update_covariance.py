import numpy as np


def update_covariance(P, H, R):
    """The state covariance after one EKF update (Joseph form or the short form).

    P: the n×n state covariance (nested lists), symmetric positive definite.
    H: the 2×n measurement Jacobian (nonzero in the pose's and one landmark's columns).
    R: the 2×2 measurement-noise covariance (m², m·rad, rad²), possibly correlated.
    Returns P⁺ = (I − K H) P (I − K H)ᵀ + K R Kᵀ with K = P Hᵀ (H P Hᵀ + R)⁻¹, shape (n, n).
    """
    raise NotImplementedError("compute S, K, then P⁺")
