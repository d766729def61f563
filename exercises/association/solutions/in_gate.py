import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 1:
        # d2 = z**2 with z standard normal: P(|z| < c) = confidence
        c = NormalDist().inv_cdf(0.5 + confidence / 2)
        threshold = c * c
    else:
        # chi-square with 2 DOF is exponential: CDF(x) = 1 - exp(-x / 2)
        threshold = -2.0 * math.log(1.0 - confidence)
    return d2 < threshold
