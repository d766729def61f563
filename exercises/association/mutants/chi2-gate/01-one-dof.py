# mistake: the one-degree-of-freedom threshold for every measurement
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    c = NormalDist().inv_cdf((1 + confidence) / 2)
    return d2 < c * c
