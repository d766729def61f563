# mistake: writes the predicted covariance over np.asarray(sigma, dtype=float), which is the caller's own matrix when sigma is a float array
import math

import numpy as np


def predict_covariance(pose, u, sigma, motion_cov):
    theta = pose[2]
    rot1, trans, _ = u
    c, s = math.cos(theta + rot1), math.sin(theta + rot1)
    G = np.array([[1.0, 0.0, -trans * s], [0.0, 1.0, trans * c], [0.0, 0.0, 1.0]])
    V = np.array([[-trans * s, c, 0.0], [trans * c, s, 0.0], [1.0, 0.0, 1.0]])
    S = np.asarray(sigma, dtype=float)
    S[:] = G @ S @ G.T + V @ np.asarray(motion_cov, dtype=float) @ V.T
    return S
