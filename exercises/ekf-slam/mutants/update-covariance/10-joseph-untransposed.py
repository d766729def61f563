# mistake: (I − K H) P (I − K H) + K R Kᵀ, the right factor not transposed
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    A = np.eye(len(P)) - K @ H
    return A @ P @ A + K @ R @ K.T
