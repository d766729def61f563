# mistake: kron(R, I) instead of kron(I, R): the noise's entries land on the wrong rows
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(R, np.eye(k))
    return float(nu @ np.linalg.solve(S, nu))
