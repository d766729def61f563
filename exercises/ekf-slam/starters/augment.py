import math

import numpy as np


def augment(mu, P, z, R):
    """The covariance with a landmark first seen at z = (range m, bearing rad) appended last.

    mu: the state (x_r, y_r, θ_r, x_1, y_1, ...), length n = 3 + 2N.
    P: its n×n covariance (nested lists). R: the 2×2 measurement-noise covariance.
    Returns the (n + 2)×(n + 2) covariance [[P, (Gr P_r·)ᵀ], [Gr P_r·, Gr P_rr Grᵀ + Gz R Gzᵀ]].
    """
    raise NotImplementedError("build Gr and Gz, then the blocks of the new covariance")
