# mistake: S⁻¹ taken entry by entry (1 / S), right only for a diagonal S
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    S = H @ P @ H.T + R
    K = P @ H.T @ (1.0 / S)
    return (np.eye(len(P)) - K @ H) @ P
