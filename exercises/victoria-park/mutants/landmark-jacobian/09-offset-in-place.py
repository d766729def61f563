# mistake: computes the offset in place, in the landmark array it was given
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    d = np.asarray(landmark, dtype=float)
    d -= np.asarray(pose[:2], dtype=float)
    h = rt @ d
    jac = np.zeros((2, 5))
    jac[:, :2] = -rt
    jac[:, 2] = [h[1], -h[0]]
    jac[:, 3:] = rt
    return jac
