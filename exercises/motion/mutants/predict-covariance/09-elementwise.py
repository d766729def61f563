# mistake: uses * (element-wise) instead of @ (matrix product)
import math

import numpy as np

def predict_covariance(pose, u, sigma, motion_cov):
    t = pose[2] + u[0]
    c, s = math.cos(t), math.sin(t)
    d = u[1]
    G = np.array([[1, 0, -d * s], [0, 1, d * c], [0, 0, 1]])
    V = np.array([[-d * s, c, 0], [d * c, s, 0], [1, 0, 1]])
    return G * np.array(sigma) * G.T + V * np.array(motion_cov) * V.T
