# method: S built block by block in a loop, then whitened with its Cholesky factor (d² = |L⁻¹ν|²)
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    S = H @ P @ H.T
    for i in range(0, len(nu), 2):
        S[i : i + 2, i : i + 2] += R
    L = np.linalg.cholesky(S)
    w = np.linalg.solve(L, nu)
    return float(w @ w)
