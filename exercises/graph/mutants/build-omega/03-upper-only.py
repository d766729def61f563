# mistake: symmetric-only fill forgotten: -w goes to the upper triangle only
import numpy as np


def build_omega(n, edges):
    omega = np.zeros((n, n))
    for i, j, w in edges:
        a, b = min(i, j), max(i, j)
        omega[a, a] += w
        omega[b, b] += w
        omega[a, b] -= w
    return omega
