# method: the short form P − K S Kᵀ, symmetrised
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    S = H @ P @ H.T + R
    K = P @ H.T @ np.linalg.inv(S)
    out = P - K @ S @ K.T
    return (out + out.T) / 2
