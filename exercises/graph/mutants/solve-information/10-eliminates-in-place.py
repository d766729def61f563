# mistake: Gaussian elimination on np.asarray(omega, dtype=float), which is the caller's own matrix when omega is a float array
import numpy as np


def solve_information(omega, xi):
    A = np.asarray(omega, dtype=float)
    b = np.array(xi, dtype=float)
    n = len(b)
    for k in range(n):
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            A[i, k:] -= f * A[k, k:]
            b[i] -= f * b[k]
    mu = np.zeros(n)
    for i in reversed(range(n)):
        mu[i] = (b[i] - A[i, i + 1:] @ mu[i + 1:]) / A[i, i]
    return mu
