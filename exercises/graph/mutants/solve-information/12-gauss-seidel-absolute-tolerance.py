# mistake: Gauss-Seidel sweeps until no entry moves by more than 1e-9 (an absolute tolerance: on a stiff, weakly anchored chain the sweeps crawl, and it stops well before the answer)
import numpy as np


def solve_information(omega, xi):
    A = np.array(omega, dtype=float)
    b = np.array(xi, dtype=float)
    n = len(b)
    mu = np.zeros(n)
    for _ in range(20000):
        biggest = 0.0
        for i in range(n):
            new = (b[i] - A[i] @ mu + A[i, i] * mu[i]) / A[i, i]
            biggest = max(biggest, abs(new - mu[i]))
            mu[i] = new
        if biggest < 1e-9:
            break
    return mu
