# method: complex-step differentiation of the prediction, exact to rounding
import cmath

import numpy as np


def _h(v):
    x, y, t, lx, ly = v
    c, s = cmath.cos(t), cmath.sin(t)
    dx, dy = lx - x, ly - y
    return np.array([c * dx + s * dy, -s * dx + c * dy])


def landmark_jacobian(pose, landmark):
    v = np.array([pose[0], pose[1], pose[2], landmark[0], landmark[1]], dtype=complex)
    step = 1e-20
    jac = np.zeros((2, 5))
    for k in range(5):
        w = v.copy()
        w[k] += 1j * step
        jac[:, k] = _h(w).imag / step
    return jac
