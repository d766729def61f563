# mistake: the heading column from the world-frame offset l - t instead of h = R^T (l - t)
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    dx, dy = landmark[0] - pose[0], landmark[1] - pose[1]
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 2] = [dy, -dx]
    jac[:, 3:] = rt
    return jac
