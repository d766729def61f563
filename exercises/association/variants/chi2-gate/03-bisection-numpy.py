# method: bisection on erf for the 1-DOF quantile, numpy for 2 DOF; returns a numpy bool
import math

import numpy as np


def normal_two_sided(p):
    lo, hi = 0.0, 10.0
    for _ in range(100):
        mid = (lo + hi) / 2
        if math.erf(mid / math.sqrt(2)) < p:
            lo = mid
        else:
            hi = mid
    return (lo + hi) / 2


def in_gate(d2, dof, confidence):
    if dof == 1:
        threshold = np.float64(normal_two_sided(confidence)) ** 2
    else:
        threshold = -2 * np.log(1 - np.float64(confidence))
    return np.float64(d2) < threshold
