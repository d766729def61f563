# mistake: the heading column left at zero ("the heading is not a position")
import numpy as np


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = np.sqrt(q)
    H = np.zeros((2, 5))
    H[0] = [-dx / r, -dy / r, 0, dx / r, dy / r]
    H[1] = [dy / q, -dx / q, 0, -dy / q, dx / q]
    return H
