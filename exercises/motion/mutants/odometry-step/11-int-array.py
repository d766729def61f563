# mistake: builds the new pose in np.array(pose), an integer array when the pose's numbers are whole, so the moved position is truncated
import math

import numpy as np


def odometry_step(pose, u):
    x = np.array(pose)
    rot1, trans, rot2 = u
    heading = x[2] + rot1
    x[0] += trans * math.cos(heading)
    x[1] += trans * math.sin(heading)
    x[2] = heading + rot2
    return x
