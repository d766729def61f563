# mistake: moves the pose without noise, then adds Gaussian noise to x, y and theta directly
import math

import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rng = np.random.default_rng(seed)
    x, y, theta = pose
    rot1, trans, rot2 = u
    a1, a2, a3, a4 = alphas
    s1 = math.sqrt(a1 * rot1**2 + a2 * trans**2)
    s2 = math.sqrt(a3 * trans**2 + a4 * (rot1**2 + rot2**2))
    s3 = math.sqrt(a1 * rot2**2 + a2 * trans**2)
    h = theta + rot1
    px = x + trans * math.cos(h) + rng.normal(0.0, s2, n)
    py = y + trans * math.sin(h) + rng.normal(0.0, s2, n)
    pt = h + rot2 + rng.normal(0.0, s1, n) + rng.normal(0.0, s3, n)
    return np.column_stack([px, py, np.arctan2(np.sin(pt), np.cos(pt))])
