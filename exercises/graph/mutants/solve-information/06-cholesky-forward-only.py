# mistake: Cholesky factorisation, but only the forward solve L y = xi; the back solve L^T mu = y is missing
import numpy as np


def solve_information(omega, xi):
    L = np.linalg.cholesky(np.asarray(omega, dtype=float))
    return np.linalg.solve(L, np.asarray(xi, dtype=float))
