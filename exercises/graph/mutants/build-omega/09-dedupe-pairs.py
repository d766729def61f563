# mistake: edges stored in a dict keyed by the unordered pair, so a repeated (or reversed) pair overwrites the earlier measurement
import numpy as np


def build_omega(n, edges):
    info = {}
    for i, j, w in edges:
        info[(min(i, j), max(i, j))] = w
    omega = np.zeros((n, n))
    for (i, j), w in info.items():
        omega[i, i] += w
        omega[j, j] += w
        omega[i, j] -= w
        omega[j, i] -= w
    return omega
