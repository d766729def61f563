# method: Kabsch/Umeyama: SVD of the cross-covariance with the det(V Uᵀ) correction
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    H = (P - pm).T @ (Q - qm)
    U, _, Vt = np.linalg.svd(H)
    d = 1.0 if np.linalg.det(Vt.T @ U.T) >= 0 else -1.0
    R = Vt.T @ np.diag([1.0, d]) @ U.T
    t = qm - R @ pm
    return [float(np.arctan2(R[1, 0], R[0, 0])), float(t[0]), float(t[1])]
