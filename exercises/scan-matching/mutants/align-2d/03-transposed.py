# mistake: R = U Vᵀ, the rotation from Q back to P
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - pm).T @ (Q - qm))
    d = 1.0 if np.linalg.det(U @ Vt) >= 0 else -1.0
    R = U @ np.diag([1.0, d]) @ Vt
    t = qm - R @ pm
    return [float(np.arctan2(R[1, 0], R[0, 0])), float(t[0]), float(t[1])]
