# method: scatter the -w with numpy.add.at, then set the diagonal to minus each row's sum (a graph Laplacian)
import numpy as np


def build_omega(n, edges):
    omega = np.zeros((n, n))
    if edges:
        i = np.array([e[0] for e in edges], dtype=int)
        j = np.array([e[1] for e in edges], dtype=int)
        w = np.array([e[2] for e in edges], dtype=float)
        np.add.at(omega, (i, j), -w)
        np.add.at(omega, (j, i), -w)
    np.fill_diagonal(omega, -omega.sum(axis=1))
    return omega
