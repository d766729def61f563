# method: the distribution function by integrating the χ² density numerically (Simpson's rule)
import math

import numpy as np


def density(t, dof):
    if t <= 0:
        return 0.0 if dof > 2 else 0.5
    return t ** (dof / 2 - 1) * math.exp(-t / 2) / (2 ** (dof / 2) * math.gamma(dof / 2))


def joint_compatible(H, P, R, nu, confidence):
    H, P, R, nu = (np.array(a, dtype=float) for a in (H, P, R, nu))
    dof = len(nu)
    S = H @ P @ H.T + np.kron(np.eye(dof // 2), R)
    d2 = float(nu @ np.linalg.solve(S, nu))
    steps = 400
    h = d2 / steps
    total = density(0, dof) + density(d2, dof)
    for i in range(1, steps):
        total += (4 if i % 2 else 2) * density(i * h, dof)
    return total * h / 3 < confidence
