# mistake: adds M directly instead of V M V^T
import math

import numpy as np

def predict_covariance(pose, u, sigma, motion_cov):
    t = pose[2] + u[0]
    G = np.array([[1, 0, -u[1] * math.sin(t)], [0, 1, u[1] * math.cos(t)], [0, 0, 1]])
    return G @ np.array(sigma) @ G.T + np.array(motion_cov)
