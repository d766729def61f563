# mistake: returns True for candidates outside the gate
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 2:
        threshold = -2 * math.log(1 - confidence)
    else:
        threshold = NormalDist().inv_cdf((1 + confidence) / 2) ** 2
    return d2 > threshold
