# method: Joseph form with the gain from a linear solve (S Kᵀ = H P), never inverting S
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.asarray(P, dtype=float), np.asarray(H, dtype=float), np.asarray(R, dtype=float)
    S = H @ P @ H.T + R
    K = np.linalg.solve(S, H @ P).T
    A = np.eye(P.shape[0]) - K @ H
    return A @ P @ A.T + K @ R @ K.T
