# mistake: the pairings' individual d² added up (cross-covariance blocks ignored)
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    total = 0.0
    for i in range(0, len(nu), 2):
        Hi = H[i : i + 2]
        S = Hi @ P @ Hi.T + R
        total += nu[i : i + 2] @ np.linalg.solve(S, nu[i : i + 2])
    return float(total)
