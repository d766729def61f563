# mistake: negates a numpy view of the landmark block in place, so both blocks end up negated
import numpy as np


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    q = dx * dx + dy * dy
    r = np.sqrt(q)
    H = np.zeros((2, 5))
    H[:, 3:5] = [[dx / r, dy / r], [-dy / q, dx / q]]
    robot = H[:, 3:5]  # a view, not a copy
    robot *= -1
    H[:, 0:2] = robot
    H[1, 2] = -1.0
    return H
