# mistake: returns the 5 x 2 transpose (one row per variable)
import numpy as np


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = np.sqrt(q)
    H = np.array([
        [-dx / r, -dy / r, 0.0, dx / r, dy / r],
        [dy / q, -dx / q, -1.0, -dy / q, dx / q],
    ])
    return H.T
