# mistake: eliminates on b = np.array(xi), an integer array when the information vector holds whole numbers, so the right-hand side is truncated
import numpy as np


def solve_information(omega, xi):
    A = np.array(omega, dtype=float)
    b = np.array(xi)
    n = len(b)
    for k in range(n):
        for i in range(k + 1, n):
            f = A[i, k] / A[k, k]
            A[i, k:] -= f * A[k, k:]
            b[i] = b[i] - f * b[k]
    mu = np.zeros(n)
    for i in reversed(range(n)):
        mu[i] = (b[i] - A[i, i + 1:] @ mu[i + 1:]) / A[i, i]
    return mu
