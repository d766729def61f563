# mistake: S = H P Hᵀ, the measurements taken as exact
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, nu = (np.array(a, dtype=float) for a in (H, P, nu))
    S = H @ P @ H.T
    return float(nu @ np.linalg.pinv(S) @ nu)
