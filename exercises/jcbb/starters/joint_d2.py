import numpy as np


def joint_d2(H, P, R, nu):
    """Joint squared Mahalanobis distance of a hypothesis with k pairings.

    H: the 2k×n stacked Jacobians (rows 2i, 2i+1: pairing i). P: the n×n state covariance.
    R: the 2×2 noise of one measurement (the same for every pairing). nu: the stacked
    innovation, length 2k. Returns νᵀ S⁻¹ ν with S = H P Hᵀ + blockdiag(R, ..., R).
    """
    raise NotImplementedError("build S, then solve")
