# method: scipy.stats.norm.rvs for the noise and homogeneous SE(2) matrices for the motion
import numpy as np
from scipy.stats import norm


def se2(x, y, t):
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, -s, x], [s, c, y], [0.0, 0.0, 1.0]])


def sample_motion(pose, u, alphas, n, seed):
    a1, a2, a3, a4 = alphas
    rot1, trans, rot2 = u
    var = [a1 * rot1**2 + a2 * trans**2, a3 * trans**2 + a4 * (rot1**2 + rot2**2), a1 * rot2**2 + a2 * trans**2]
    noise = norm.rvs(size=(n, 3), random_state=np.random.default_rng(seed)) * np.sqrt(var)
    start = se2(*pose)
    rows = []
    for e1, e2, e3 in noise:
        m = start @ se2(0, 0, rot1 + e1) @ se2(trans + e2, 0, rot2 + e3)
        rows.append([m[0, 2], m[1, 2], np.arctan2(m[1, 0], m[0, 0])])
    return np.array(rows)
