import numpy as np


def low_variance_resample(weights, u):
    """Low-variance (systematic) resampling.

    weights: N importance weights (not normalised; their sum is positive).
    u: one uniform number in [0, 1).
    Returns the N indices (0-based) of the surviving particles: particle m takes the first
    index whose normalised cumulative weight reaches (u + m) / N.
    """
    raise NotImplementedError("normalise, accumulate, and walk the N thresholds (u + m) / N")
