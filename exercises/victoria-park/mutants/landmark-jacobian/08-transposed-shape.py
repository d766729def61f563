# mistake: returns the 5x2 transpose (one row per variable)
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    h = rt @ np.array([landmark[0] - pose[0], landmark[1] - pose[1]])
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 2] = [h[1], -h[0]]
    jac[:, 3:] = rt
    return jac.T
