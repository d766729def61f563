import math

import numpy as np


def predict_covariance(pose, u, sigma, motion_cov):
    """The EKF's predicted covariance G @ sigma @ G.T + V @ M @ V.T for the odometry model.

    pose: (x, y, theta), the mean before the motion (m, m, rad).
    u: (rot1, trans, rot2), the odometry (rad, m, rad).
    sigma: 3x3 covariance of the pose.  motion_cov: 3x3 covariance M of (rot1, trans, rot2).
    G = d(x', y', theta')/d(x, y, theta), V = d(x', y', theta')/d(rot1, trans, rot2).
    Returns the 3x3 predicted covariance.
    """
    raise NotImplementedError("build G and V at (pose, u), then G S G^T + V M V^T")
