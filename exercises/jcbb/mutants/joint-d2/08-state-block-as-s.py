# mistake: the state covariance used as if it were the innovations' (P block instead of H P Hᵀ)
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = np.kron(np.eye(k), R) + P[: 2 * k, : 2 * k]
    return float(nu @ np.linalg.solve(S, nu))
