# mistake: solves exp(-x/2) = p instead of 1 - exp(-x/2) = p (the quantile of 1 - p)
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 2:
        threshold = -2 * math.log(confidence)
    else:
        threshold = NormalDist().inv_cdf((1 + confidence) / 2) ** 2
    return d2 < threshold
