# method: one Jacobian J = [G V] applied to the joint covariance blockdiag(Sigma, M)
import math

import numpy as np


def predict_covariance(pose, u, sigma, motion_cov):
    rot1, trans, _ = u
    c, s = math.cos(pose[2] + rot1), math.sin(pose[2] + rot1)
    J = np.array(
        [
            [1, 0, -trans * s, -trans * s, c, 0],
            [0, 1, trans * c, trans * c, s, 0],
            [0, 0, 1, 1, 0, 1],
        ],
        dtype=float,
    )
    P = np.zeros((6, 6))
    P[:3, :3] = sigma
    P[3:, 3:] = motion_cov
    return J @ P @ J.T
