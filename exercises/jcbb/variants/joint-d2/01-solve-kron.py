# method: block-diagonal noise with np.kron, then a linear solve
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.asarray(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    return float(nu @ np.linalg.solve(S, nu))
