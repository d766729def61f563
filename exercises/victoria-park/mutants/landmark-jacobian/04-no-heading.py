# mistake: forgets that h depends on theta (the heading column left zero)
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 3:] = rt
    return jac
