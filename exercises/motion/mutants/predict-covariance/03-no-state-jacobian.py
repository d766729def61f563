# mistake: Sigma + V M V^T: the old covariance is not carried through G
import math

import numpy as np

def predict_covariance(pose, u, sigma, motion_cov):
    t = pose[2] + u[0]
    c, s = math.cos(t), math.sin(t)
    V = np.array([[-u[1] * s, c, 0], [u[1] * c, s, 0], [1, 0, 1]])
    return np.array(sigma) + V @ np.array(motion_cov) @ V.T
