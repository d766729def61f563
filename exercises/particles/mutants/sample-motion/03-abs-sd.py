# mistake: uses alpha1*|rot1| + alpha2*|trans| as the standard deviation (no squares, no root)
import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rng = np.random.default_rng(seed)
    x, y, theta = pose
    rot1, trans, rot2 = u
    a1, a2, a3, a4 = alphas
    r1 = rot1 + rng.normal(0.0, a1 * abs(rot1) + a2 * abs(trans), n)
    t = trans + rng.normal(0.0, a3 * abs(trans) + a4 * (abs(rot1) + abs(rot2)), n)
    r2 = rot2 + rng.normal(0.0, a1 * abs(rot2) + a2 * abs(trans), n)
    h = theta + r1
    return np.column_stack([x + t * np.cos(h), y + t * np.sin(h), np.arctan2(np.sin(h + r2), np.cos(h + r2))])
