import math

import numpy as np


def loop_candidates(poses, marginals, cross, gap, confidence):
    """Indices i <= k - gap (k = len(poses) - 1, the current pose) whose relative position to
    pose k passes the chi-square gate with 2 degrees of freedom, in increasing order.

    poses: n x 3 (x, y, theta); marginals[i] = Sigma_ii and cross[i] = Sigma_ik, n x 3 x 3 each.
    d_i^2 = r^T S^-1 r with r the first two entries of x_i^-1 (+) x_k and S the top-left 2x2
    block of J [[Sigma_ii, Sigma_ik], [Sigma_ik^T, Sigma_kk]] J^T.
    """
    raise NotImplementedError("loop over the searched poses and gate d^2 at chi2_2(confidence)")
