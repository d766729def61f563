# mistake: clips the confidence to 0.999 "to avoid log(0)", shrinking the highest-confidence gates
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    p = min(confidence, 0.999)
    if dof == 2:
        threshold = -2 * math.log(1 - p)
    else:
        threshold = NormalDist().inv_cdf((1 + p) / 2) ** 2
    return d2 < threshold
