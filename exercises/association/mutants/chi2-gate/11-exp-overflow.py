# mistake: writes the 2-DOF CDF as 1 - 1/exp(d2/2), which overflows for a far-off candidate (d2 above about 1420)
import math
from statistics import NormalDist


def in_gate(d2, dof, confidence):
    if dof == 1:
        c = NormalDist().inv_cdf(0.5 + confidence / 2)
        return d2 < c * c
    return 1 - 1 / math.exp(d2 / 2) < confidence
