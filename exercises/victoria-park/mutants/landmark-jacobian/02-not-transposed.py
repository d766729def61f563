# mistake: R(theta) where R(theta)^T belongs, in both blocks and in the heading column
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    r = np.array([[c, -s], [s, c]])
    dr = np.array([[-s, -c], [c, -s]])
    d = np.array([landmark[0] - pose[0], landmark[1] - pose[1]])
    jac = np.zeros((2, 5))
    jac[:, :2] = -r
    jac[:, 2] = dr @ d
    jac[:, 3:] = r
    return jac
