# mistake: an integer array silently truncates fractional information (0.01 becomes 0)
import numpy as np


def build_omega(n, edges):
    omega = np.zeros((n, n), dtype=int)
    for i, j, w in edges:
        omega[i, i] = omega[i, i] + w
        omega[j, j] = omega[j, j] + w
        omega[i, j] = omega[i, j] - w
        omega[j, i] = omega[j, i] - w
    return omega
