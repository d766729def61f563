# method: scipy's SVD, every candidate's depths compared by the worst one
import numpy as np
from scipy import linalg


def decompose_essential(E, x1, x2):
    U, _, Vt = linalg.svd(np.asarray(E, dtype=float))
    U = U @ np.diag([1.0, 1.0, np.sign(linalg.det(U))]) if linalg.det(U) < 0 else U
    Vt = np.diag([1.0, 1.0, np.sign(linalg.det(Vt))]) @ Vt if linalg.det(Vt) < 0 else Vt
    W = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    a, b = np.asarray(x1, dtype=float), np.asarray(x2, dtype=float)
    best, best_score = None, -np.inf
    for R in (U @ W @ Vt, U @ W.T @ Vt):
        for t in (U[:, 2], -U[:, 2]):
            z, *_ = linalg.lstsq(np.column_stack([-(R @ a), b]), t)
            score = min(z)
            if score > best_score:
                best, best_score = np.column_stack([R, t]), score
    return best
