# mistake: R tiled over every block (np.tile), as if all readings shared one noise
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.tile(R, (k, k))
    return float(nu @ np.linalg.solve(S, nu))
