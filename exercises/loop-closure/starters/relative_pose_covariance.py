import math

import numpy as np


def relative_pose_covariance(xi, xj, P):
    """Covariance (3x3) of r = xi^-1 (+) xj, linearised at the given poses.

    xi, xj: poses (x, y, theta) in metres and radians.
    P: their 6x6 joint covariance, rows and columns in the order (xi, yi, thi, xj, yj, thj).
    """
    raise NotImplementedError("J = [Ji | Jj] (3x6); return J @ P @ J^T")
