# method: information form, (P⁻¹ + Hᵀ R⁻¹ H)⁻¹
import numpy as np


def update_covariance(P, H, R):
    P, H, R = np.array(P, dtype=float), np.array(H, dtype=float), np.array(R, dtype=float)
    info = np.linalg.inv(P) + H.T @ np.linalg.solve(R, H)
    return np.linalg.inv(info)
