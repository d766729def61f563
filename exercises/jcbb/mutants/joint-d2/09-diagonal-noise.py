# mistake: R read as two variances, its range-bearing correlation dropped
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), np.diag(np.diag(R)))
    return float(nu @ np.linalg.solve(S, nu))
