# mistake: central differences on np.array of the five inputs, an integer array when they are whole numbers, so the step is truncated away
import math

import numpy as np


def _h(v):
    dx, dy = v[3] - v[0], v[4] - v[1]
    return np.array([math.hypot(dx, dy), math.atan2(dy, dx) - v[2]])


def range_bearing_jacobian(xr, yr, thr, xj, yj):
    v = np.array([xr, yr, thr, xj, yj])
    step = 1e-6
    J = np.zeros((2, 5))
    for k in range(5):
        plus, minus = v.copy(), v.copy()
        plus[k] += step
        minus[k] -= step
        d = _h(plus) - _h(minus)
        d[1] = math.remainder(d[1], 2 * math.pi)
        J[:, k] = d / (2 * step)
    return J
