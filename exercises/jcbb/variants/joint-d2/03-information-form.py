# method: Woodbury: S⁻¹ = N⁻¹ − N⁻¹ H (P⁻¹ + Hᵀ N⁻¹ H)⁻¹ Hᵀ N⁻¹ with N = blockdiag(R)
import numpy as np


def joint_d2(H, P, R, nu):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    N_inv = np.kron(np.eye(k), np.linalg.inv(R))
    inner = np.linalg.inv(P) + H.T @ N_inv @ H
    S_inv = N_inv - N_inv @ H @ np.linalg.solve(inner, H.T @ N_inv)
    return float(nu @ S_inv @ nu)
