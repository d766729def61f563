# method: least squares (numpy.linalg.lstsq), which for a square invertible Omega is the exact solution
import numpy as np


def solve_information(omega, xi):
    mu, *_ = np.linalg.lstsq(np.array(omega, dtype=float), np.array(xi, dtype=float), rcond=None)
    return mu
