# mistake: R read as two variances, its off-diagonal (range-bearing correlation) dropped
import numpy as np


def update_covariance(P, H, R):
    P, H = np.array(P, dtype=float), np.array(H, dtype=float)
    S = H @ P @ H.T + np.diag([R[0][0], R[1][1]])
    K = P @ H.T @ np.linalg.inv(S)
    return (np.eye(len(P)) - K @ H) @ P
