# mistake: R = V Uᵀ from the SVD without the det correction: a reflection on mirrored inputs
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - pm).T @ (Q - qm))
    R = Vt.T @ U.T
    t = qm - R @ pm
    return [float(np.arctan2(R[1, 0], R[0, 0])), float(t[0]), float(t[1])]
