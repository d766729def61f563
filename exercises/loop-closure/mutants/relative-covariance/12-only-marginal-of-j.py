# mistake: takes pose i as certain (as if it were the anchor) and returns Jj Sjj Jj^T only
import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    Jj = np.array([[ci, si, 0.0], [-si, ci, 0.0], [0.0, 0.0, 1.0]])
    return Jj @ np.asarray(P, dtype=float)[3:, 3:] @ Jj.T
