# mistake: P + K H P, the information added instead of the uncertainty removed
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    return P + K @ H @ P
