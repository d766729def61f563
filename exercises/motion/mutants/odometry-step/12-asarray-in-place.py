# mistake: adds the motion in place to np.asarray(pose, dtype=float), which is the caller's own array when pose is a float array
import math

import numpy as np


def odometry_step(pose, u):
    x = np.asarray(pose, dtype=float)
    rot1, trans, rot2 = u
    heading = x[2] + rot1
    x += [trans * math.cos(heading), trans * math.sin(heading), rot1 + rot2]
    return x
