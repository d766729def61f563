# mistake: compares d = sqrt(d2) with a threshold meant for d2
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 2:
        threshold = -2 * math.log(1 - confidence)
    else:
        threshold = NormalDist().inv_cdf((1 + confidence) / 2) ** 2
    return math.sqrt(d2) < threshold
