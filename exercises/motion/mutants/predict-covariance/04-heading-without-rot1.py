# mistake: Jacobians evaluated at theta instead of theta + rot1
import math

import numpy as np

def predict_covariance(pose, u, sigma, motion_cov):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    d = u[1]
    G = np.array([[1, 0, -d * s], [0, 1, d * c], [0, 0, 1]])
    V = np.array([[-d * s, c, 0], [d * c, s, 0], [1, 0, 1]])
    return G @ np.array(sigma) @ G.T + V @ np.array(motion_cov) @ V.T
