# method: Cholesky factor L, then the forward solve L y = xi and the back solve L^T mu = y
import numpy as np


def solve_information(omega, xi):
    L = np.linalg.cholesky(np.asarray(omega, dtype=float))
    y = np.linalg.solve(L, np.asarray(xi, dtype=float))
    return np.linalg.solve(L.T, y)
