# mistake: R added to the first 2×2 block only
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    S = H @ P @ H.T
    S[:2, :2] += R
    return float(nu @ np.linalg.solve(S, nu))
