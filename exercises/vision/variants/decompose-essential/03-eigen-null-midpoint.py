# method: t from the eigenvector of E Eᵀ with the smallest eigenvalue, midpoint triangulation
import numpy as np


def decompose_essential(E, x1, x2):
    E = np.asarray(E, dtype=float)
    x1 = np.asarray(x1, dtype=float)
    x2 = np.asarray(x2, dtype=float)
    vals, vecs = np.linalg.eigh(E @ E.T)
    u3 = vecs[:, np.argmin(vals)]
    U, _, Vt = np.linalg.svd(E)
    if np.linalg.det(U) < 0:
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    rotations = [U @ W @ Vt, U @ W.T @ Vt]
    for R in rotations:
        for t in (u3, -u3):
            # camera 2's centre in frame 1 is c2 = -Rᵀ t; rays d1 = x1 and d2 = Rᵀ x2
            c2 = -R.T @ t
            d1, d2 = x1, R.T @ x2
            A = np.array([[d1 @ d1, -d1 @ d2], [d1 @ d2, -d2 @ d2]])
            rhs = np.array([d1 @ c2, d2 @ c2])
            s1, s2 = np.linalg.solve(A, rhs)
            X = 0.5 * (s1 * d1 + c2 + s2 * d2)
            if X[2] > 0 and (R @ X + t)[2] > 0:
                return np.column_stack([R, t])
    raise ValueError("no candidate")
