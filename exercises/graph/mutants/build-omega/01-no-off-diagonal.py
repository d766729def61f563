# mistake: only the diagonal is filled; the -w coupling the two poses is missing
import numpy as np


def build_omega(n, edges):
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
    return omega
