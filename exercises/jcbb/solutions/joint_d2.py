import numpy as np


def joint_d2(H, P, R, nu):
    """Joint squared Mahalanobis distance of a hypothesis with k pairings."""
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    return float(nu @ np.linalg.solve(S, nu))
