import math

import numpy as np


def robust_weights(kind, s, k):
    """IRLS weights w(s) = rho'(s) of squared errors s for one robust kernel.

    kind: "l2", "huber", "cauchy" or "dcs".
    s: a sequence of squared Mahalanobis errors e^T Omega e (each >= 0), possibly empty.
    k: the kernel width (> 0); the boundary is at s = k**2 (for DCS, Phi = k**2).
    Returns a 1-D array of weights, one per entry of s, each in (0, 1].
    """
    raise NotImplementedError("differentiate each kernel with respect to s")
