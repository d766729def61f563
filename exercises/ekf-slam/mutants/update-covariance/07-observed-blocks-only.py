# mistake: only the rows and columns H touches (pose, observed landmark) are updated
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
    full = (np.eye(len(P)) - K @ H) @ P
    touched = np.flatnonzero(np.any(H != 0, axis=0))
    out = P.copy()
    out[np.ix_(touched, touched)] = full[np.ix_(touched, touched)]
    return out
