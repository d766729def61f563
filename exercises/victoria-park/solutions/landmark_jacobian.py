import math

import numpy as np


def landmark_jacobian(pose, landmark):
    x, y, theta = (float(v) for v in pose)
    c, s = math.cos(theta), math.sin(theta)
    rt = np.array([[c, s], [-s, c]])  # R(theta)^T
    d = np.array([float(landmark[0]) - x, float(landmark[1]) - y])
    h = rt @ d  # the landmark in the robot's frame
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 2] = [h[1], -h[0]]
    jac[:, 3:] = rt
    return jac
