# mistake: one-sided normal quantile inv_cdf(p) for one DOF (d2 = z² needs P(|z| < c) = p)
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 1:
        threshold = NormalDist().inv_cdf(confidence) ** 2
    else:
        threshold = -2 * math.log(1 - confidence)
    return d2 < threshold
