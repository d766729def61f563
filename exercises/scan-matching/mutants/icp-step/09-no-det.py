# mistake: the pairs aligned by SVD without the det correction
import numpy as np


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    M = Q[np.argmin(((P[:, None, :] - Q[None, :, :]) ** 2).sum(axis=2), axis=1)]
    pm, qm = P.mean(axis=0), M.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - pm).T @ (M - qm))
    R = Vt.T @ U.T
    t = qm - R @ pm
    return [float(np.arctan2(R[1, 0], R[0, 0])), float(t[0]), float(t[1])]
