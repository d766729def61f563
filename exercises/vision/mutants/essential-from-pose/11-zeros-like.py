# mistake: fills E into np.zeros_like(R), an integer array when R's entries are whole numbers (a quarter turn, the identity)
import numpy as np


def essential_matrix(t, R):
    tx = [[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]]
    E = np.zeros_like(R)
    for i in range(3):
        for j in range(3):
            E[i][j] = sum(tx[i][k] * R[k][j] for k in range(3))
    return E
