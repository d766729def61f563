# mistake: the size is inferred from the largest pose index in the edges, ignoring n
import numpy as np


def build_omega(n, edges):
    if not edges:
        return np.zeros((n, n))
    size = max(max(i, j) for i, j, _ in edges) + 1
    omega = np.zeros((size, size))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
    return omega
