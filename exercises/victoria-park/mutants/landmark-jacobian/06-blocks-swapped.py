# mistake: returns [B | A], the landmark's columns first
import math

import numpy as np


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    rt = np.array([[c, s], [-s, c]])
    h = rt @ np.array([landmark[0] - pose[0], landmark[1] - pose[1]])
    a = np.column_stack([-rt, [h[1], -h[0]]])
    return np.hstack([rt, a])
