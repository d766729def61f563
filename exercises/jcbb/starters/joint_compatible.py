import math

import numpy as np


def joint_compatible(H, P, R, nu, confidence):
    """True when the stacked innovation passes the joint χ² gate with 2k degrees of freedom.

    H: the 2k×n stacked Jacobians. P: the n×n state covariance. R: one measurement's 2×2 noise.
    nu: the stacked innovation (length 2k). confidence: 0.9, 0.95 or 0.99.
    P(χ²_2k ≤ x) = 1 − exp(−x/2) · Σ_{i<k} (x/2)^i / i!
    """
    raise NotImplementedError("compute d², then compare P(χ² ≤ d²) with the confidence")
