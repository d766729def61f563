import math

import numpy as np


def closure_nis(xi, xj, P, z, info):
    """Normalised innovation squared e^T S^-1 e of a candidate edge (i, j, z, info).

    e = z^-1 (+) (xi^-1 (+) xj), angle wrapped; S = [A B] P [A B]^T + info^-1 with P the 6x6
    joint covariance of the two poses (order xi, yi, thi, xj, yj, thj) and A, B the edge's
    Jacobians.
    """
    raise NotImplementedError("compute e, A, B, S and return e @ solve(S, e)")
