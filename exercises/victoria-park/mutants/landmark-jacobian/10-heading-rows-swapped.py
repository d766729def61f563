# mistake: the heading column as (-h_x, h_y): the rows of dR^T/dtheta mixed up
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    d = np.array([landmark[0] - pose[0], landmark[1] - pose[1]])
    h = rt @ d
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 2] = [-h[0], h[1]]
    jac[:, 3:] = rt
    return jac
