# mistake: the inverse motion returned: [Rᵀ | −Rᵀt] (X1 = R X2 + t)
import numpy as np


def decompose_essential(E, x1, x2):
    E, x1, x2 = (np.array(a, dtype=float) for a in (E, x1, x2))
    U, _, Vt = np.linalg.svd(E)
    if np.linalg.det(U) < 0:
        U = -U
    if np.linalg.det(Vt) < 0:
        Vt = -Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    for R in (U @ W @ Vt, U @ W.T @ Vt):
        for t in (U[:, 2], -U[:, 2]):
            A = np.column_stack([-(R @ x1), x2])  # z2 x2 - z1 R x1 = t
            (z1, z2), *_ = np.linalg.lstsq(A, t, rcond=None)
            if z1 > 0 and z2 > 0:
                return np.column_stack([R.T, -R.T @ t])
    raise ValueError("no candidate puts the point in front of both cameras")
