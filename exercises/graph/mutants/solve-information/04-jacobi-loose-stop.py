# mistake: Jacobi iteration stopped when a step changes mu by less than 1e-6, or after 1000 steps: slow convergence stops far from the solution
import numpy as np


def solve_information(omega, xi):
    A = np.asarray(omega, dtype=float)
    b = np.asarray(xi, dtype=float)
    d = np.diag(A)
    mu = np.zeros_like(b)
    for _ in range(1000):
        new = (b - (A @ mu - d * mu)) / d
        if np.max(np.abs(new - mu)) < 1e-6:
            return new
        mu = new
    return mu
