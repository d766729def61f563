# mistake: sorts the caller's edge list in place (edges.sort()) to bring repeated pairs together
import numpy as np


def build_omega(n, edges):
    edges.sort()
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
    return omega
