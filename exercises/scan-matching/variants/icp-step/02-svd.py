# method: np.linalg.norm distances and the Kabsch SVD with the det correction
import numpy as np


def icp_step(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    dist = np.linalg.norm(P[:, None, :] - Q[None, :, :], axis=2)
    M = Q[dist.argmin(axis=1)]
    pm, qm = P.mean(axis=0), M.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - pm).T @ (M - qm))
    D = np.diag([1.0, np.sign(np.linalg.det(Vt.T @ U.T))])
    R = Vt.T @ D @ U.T
    t = qm - R @ pm
    return [float(np.arctan2(R[1, 0], R[0, 0])), float(t[0]), float(t[1])]
