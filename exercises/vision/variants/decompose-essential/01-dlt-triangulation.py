# method: linear (DLT) triangulation of the homogeneous point with P1 = [I | 0], P2 = [R | t]
import numpy as np


def decompose_essential(E, x1, x2):
    E = np.asarray(E, dtype=float)
    a = np.asarray(x1, dtype=float)
    b = np.asarray(x2, dtype=float)
    U, _, Vt = np.linalg.svd(E)
    U = U * np.sign(np.linalg.det(U))
    Vt = Vt * np.sign(np.linalg.det(Vt))
    W = np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]], dtype=float)
    P1 = np.hstack([np.eye(3), np.zeros((3, 1))])
    for R in (U @ W @ Vt, U @ W.T @ Vt):
        for t in (U[:, 2], -U[:, 2]):
            P2 = np.hstack([R, t.reshape(3, 1)])
            A = np.array(
                [
                    a[0] * P1[2] - P1[0],
                    a[1] * P1[2] - P1[1],
                    b[0] * P2[2] - P2[0],
                    b[1] * P2[2] - P2[1],
                ]
            )
            X = np.linalg.svd(A)[2][-1]
            X = X[:3] / X[3]
            if X[2] > 0 and (R @ X + t)[2] > 0:
                return np.hstack([R, t.reshape(3, 1)])
    raise ValueError("no candidate in front of both cameras")
