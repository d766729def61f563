# mistake: the Jacobian built in an array of the pose's dtype (ints when the pose is ints)
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    p = np.asarray(pose)
    c, s = math.cos(p[2]), math.sin(p[2])
    rt = np.array([[c, s], [-s, c]])
    h = rt @ (np.asarray(landmark) - p[:2])
    jac = np.zeros((2, 5), dtype=p.dtype)
    jac[:, :2] = -rt
    jac[:, 2] = [h[1], -h[0]]
    jac[:, 3:] = rt
    return jac
