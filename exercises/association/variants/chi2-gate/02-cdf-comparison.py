# method: no quantile at all: accept when the chi-square CDF at d2 is below p (erf and exp)
import math


def in_gate(d2, dof, confidence):
    if dof == 1:
        cdf = math.erf(math.sqrt(d2 / 2.0))
    else:
        cdf = 1.0 - math.exp(-d2 / 2.0)
    return cdf < confidence
