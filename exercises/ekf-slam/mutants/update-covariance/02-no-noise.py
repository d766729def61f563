# mistake: S = H P Hᵀ, the measurement treated as exact
import numpy as np


def update_covariance(P, H, R):
    P, H = np.array(P, dtype=float), np.array(H, dtype=float)
    S = H @ P @ H.T
    K = P @ H.T @ np.linalg.inv(S)
    return (np.eye(len(P)) - K @ H) @ P
