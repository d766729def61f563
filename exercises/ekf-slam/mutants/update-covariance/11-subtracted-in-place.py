# mistake: np.asarray(P, dtype=float) is the caller's own matrix when P is a float array, and K S K^T is subtracted from it in place
import numpy as np


def update_covariance(P, H, R):
    P = np.asarray(P, dtype=float)
    H = np.asarray(H, dtype=float)
    S = H @ P @ H.T + np.asarray(R, dtype=float)
    K = P @ H.T @ np.linalg.inv(S)
    P -= K @ S @ K.T
    return P
