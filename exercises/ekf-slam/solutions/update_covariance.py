import numpy as np


def update_covariance(P, H, R):
    """The state covariance after one EKF update, in Joseph form."""
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    S = H @ P @ H.T + R
    K = P @ H.T @ np.linalg.inv(S)
    A = np.eye(len(P)) - K @ H
    return A @ P @ A.T + K @ R @ K.T
