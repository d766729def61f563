import math
import statistics


def in_gate(d2, dof, confidence):
    """Chi-square gate for a candidate association.

    d2:         squared Mahalanobis distance of the innovation (dimensionless, >= 0)
    dof:        degrees of freedom = entries of the measurement (1 or 2)
    confidence: probability p in [0.5, 0.9999], e.g. 0.95

    Returns True when d2 is below the chi-square quantile with dof degrees of freedom at p,
    else False. Only the standard library and numpy are available (no scipy).
    """
    raise NotImplementedError("compute the chi-square threshold, then compare d2 with it")
