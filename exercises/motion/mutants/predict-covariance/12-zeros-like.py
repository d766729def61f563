# mistake: fills the predicted covariance into np.zeros_like(sigma), an integer array when sigma's entries are whole numbers
import math

import numpy as np


def predict_covariance(pose, u, sigma, motion_cov):
    theta = pose[2]
    rot1, trans, _ = u
    c, s = math.cos(theta + rot1), math.sin(theta + rot1)
    G = np.array([[1.0, 0.0, -trans * s], [0.0, 1.0, trans * c], [0.0, 0.0, 1.0]])
    V = np.array([[-trans * s, c, 0.0], [trans * c, s, 0.0], [1.0, 0.0, 1.0]])
    new = G @ np.array(sigma, dtype=float) @ G.T + V @ np.array(motion_cov, dtype=float) @ V.T
    out = np.zeros_like(sigma)
    for i in range(3):
        for j in range(3):
            out[i][j] = new[i, j]
    return out
