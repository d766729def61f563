# mistake: uses the noisy first turn for the direction of travel but the noise-free one for the heading
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
    r1 = rot1 + rng.normal(0.0, s1, n)
    t = trans + rng.normal(0.0, s2, n)
    r2 = rot2 + rng.normal(0.0, s3, n)
    h = theta + r1
    heading = theta + rot1 + r2
    return np.column_stack([x + t * np.cos(h), y + t * np.sin(h), np.arctan2(np.sin(heading), np.cos(heading))])
