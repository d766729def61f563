# mistake: forward differences with a 1 mm step: too coarse, worst close to the landmark
import numpy as np


def h(v):
    d = v[3:5] - v[0:2]
    phi = np.arctan2(d[1], d[0]) - v[2]
    return np.array([np.hypot(d[0], d[1]), np.arctan2(np.sin(phi), np.cos(phi))])


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    x = np.array([xr, yr, thr, xj, yj], dtype=float)
    step = 1e-3
    J = np.zeros((2, 5))
    h0 = h(x)
    for k in range(5):
        e = np.zeros(5)
        e[k] = step
        diff = h(x + e) - h0
        diff[1] = np.arctan2(np.sin(diff[1]), np.cos(diff[1]))
        J[:, k] = diff / step
    return J
