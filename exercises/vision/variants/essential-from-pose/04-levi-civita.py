# method: E_ij = sum over l, k of eps_ilk t_l R_kj with the Levi-Civita symbol (numpy.einsum)
import numpy as np


def essential_matrix(t, R):
    eps = np.zeros((3, 3, 3))
    for i, l, k in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        eps[i, l, k], eps[i, k, l] = 1.0, -1.0
    return np.einsum("ilk,l,kj->ij", eps, np.asarray(t, dtype=float), np.asarray(R, dtype=float))
