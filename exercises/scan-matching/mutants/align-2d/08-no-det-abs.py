# mistake: a reflection "fixed" by flipping the sign of the angle read from it, not by the det correction
import numpy as np


def align_2d(P, Q):
    P = np.asarray(P, dtype=float)
    Q = np.asarray(Q, dtype=float)
    pm, qm = P.mean(axis=0), Q.mean(axis=0)
    U, _, Vt = np.linalg.svd((P - pm).T @ (Q - qm))
    R = Vt.T @ U.T
    theta = float(np.arctan2(R[1, 0], R[0, 0]))
    if np.linalg.det(R) < 0:
        theta = -theta
    R = np.array([[np.cos(theta), -np.sin(theta)], [np.sin(theta), np.cos(theta)]])
    t = qm - R @ pm
    return [theta, float(t[0]), float(t[1])]
