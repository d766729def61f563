# mistake: rewrites each edge as (smaller, larger, omega) in the caller's list before filling one triangle and mirroring it
import numpy as np


def build_omega(n, edges):
    for k, (i, j, w) in enumerate(edges):
        if i > j:
            edges[k] = (j, i, w)
    omega = np.zeros((n, n))
    for i, j, w in edges:
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
    return omega + np.triu(omega, 1).T
