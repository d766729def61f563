# method: analytic G and V written out, then the two sandwiches
import math

import numpy as np


def predict_covariance(pose, u, sigma, motion_cov):
    rot1, trans, _ = u
    c, s = math.cos(pose[2] + rot1), math.sin(pose[2] + rot1)
    G = np.array([[1.0, 0.0, -trans * s], [0.0, 1.0, trans * c], [0.0, 0.0, 1.0]])
    V = np.array([[-trans * s, c, 0.0], [trans * c, s, 0.0], [1.0, 0.0, 1.0]])
    return G @ np.asarray(sigma) @ G.T + V @ np.asarray(motion_cov) @ V.T
