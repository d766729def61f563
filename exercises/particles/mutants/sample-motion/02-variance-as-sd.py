# mistake: passes the variance alpha1*rot1**2 + alpha2*trans**2 as the standard deviation
import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rng = np.random.default_rng(seed)
    x, y, theta = pose
    rot1, trans, rot2 = u
    a1, a2, a3, a4 = alphas
    r1 = rot1 + rng.normal(0.0, a1 * rot1**2 + a2 * trans**2, n)
    t = trans + rng.normal(0.0, a3 * trans**2 + a4 * (rot1**2 + rot2**2), n)
    r2 = rot2 + rng.normal(0.0, a1 * rot2**2 + a2 * trans**2, n)
    h = theta + r1
    return np.column_stack([x + t * np.cos(h), y + t * np.sin(h), np.arctan2(np.sin(h + r2), np.cos(h + r2))])
