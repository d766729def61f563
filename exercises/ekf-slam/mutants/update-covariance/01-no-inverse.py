# mistake: K = P Hᵀ, the innovation covariance never divided out
import numpy as np


def update_covariance(P, H, R):
    P, H = np.array(P, dtype=float), np.array(H, dtype=float)
    K = P @ H.T
    return (np.eye(len(P)) - K @ H) @ P
