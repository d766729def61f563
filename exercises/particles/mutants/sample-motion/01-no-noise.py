# mistake: forgets the noise: every sample is the noise-free pose
import math

import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    x, y, theta = pose
    rot1, trans, rot2 = u
    h = theta + rot1
    p = [x + trans * math.cos(h), y + trans * math.sin(h), math.remainder(h + rot2, 2 * math.pi)]
    return np.tile(p, (n, 1))
