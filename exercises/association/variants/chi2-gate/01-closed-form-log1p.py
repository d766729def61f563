# method: closed-form quantiles, statistics.NormalDist for 1 DOF and -2·log1p(-p) for 2 DOF
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 1:
        threshold = NormalDist().inv_cdf(0.5 + 0.5 * confidence) ** 2
    else:
        threshold = -2.0 * math.log1p(-confidence)
    return d2 < threshold
