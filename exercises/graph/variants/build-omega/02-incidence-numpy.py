# method: Omega = A^T W A with the edge-pose incidence matrix A (numpy)
import numpy as np


def build_omega(n, edges):
    A = np.zeros((len(edges), n))
    w = np.zeros(len(edges))
    for k, (i, j, weight) in enumerate(edges):
        A[k, i] -= 1.0
        A[k, j] += 1.0
        w[k] = weight
    return A.T @ (w[:, None] * A)
