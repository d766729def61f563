# mistake: K = P Hᵀ R⁻¹, the sensor noise in place of the innovation covariance
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    K = P @ H.T @ np.linalg.inv(R)
    A = np.eye(len(P)) - K @ H
    return A @ P @ A.T + K @ R @ K.T
