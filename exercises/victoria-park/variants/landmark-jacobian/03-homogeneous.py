# method: homogeneous matrices: h = (T^-1 [l; 1])[:2], differentiated entry by entry
import numpy as np


def landmark_jacobian(pose, landmark):
    x, y, t = np.asarray(pose, dtype=float)
    c, s = np.cos(t), np.sin(t)
    inv = np.array([[c, s, -c * x - s * y], [-s, c, s * x - c * y], [0.0, 0.0, 1.0]])
    d_inv_dt = np.array([[-s, c, s * x - c * y], [-c, -s, c * x + s * y], [0.0, 0.0, 0.0]])
    point = np.array([landmark[0], landmark[1], 1.0], dtype=float)
    # d/dx of the translation column is -R^T's first column, d/dy its second
    return np.column_stack(
        [-inv[:2, 0], -inv[:2, 1], (d_inv_dt @ point)[:2], inv[:2, 0], inv[:2, 1]]
    )
