# mistake: draws one standard-normal value per sample and uses it for both turns
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
    e = rng.standard_normal(n)
    r1 = rot1 + s1 * e
    t = trans + s2 * rng.standard_normal(n)
    r2 = rot2 + s3 * e
    h = theta + r1
    return np.column_stack([x + t * np.cos(h), y + t * np.sin(h), np.arctan2(np.sin(h + r2), np.cos(h + r2))])
