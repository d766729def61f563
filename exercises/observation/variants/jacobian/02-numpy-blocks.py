# method: numpy blocks: landmark block A, then [-A | heading column | A]
import numpy as np


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    d = np.array([xj - xr, yj - yr])
    q = d @ d
    A = np.array([d / np.sqrt(q), np.array([-d[1], d[0]]) / q])
    heading = np.array([[0.0], [-1.0]])
    return np.hstack([-A, heading, A])
