# mistake: draws the three noises once and gives every sample the same ones
import math
import random

import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rnd = random.Random(seed)
    x, y, theta = pose
    rot1, trans, rot2 = u
    a1, a2, a3, a4 = alphas
    r1 = rot1 + rnd.gauss(0.0, math.sqrt(a1 * rot1**2 + a2 * trans**2))
    t = trans + rnd.gauss(0.0, math.sqrt(a3 * trans**2 + a4 * (rot1**2 + rot2**2)))
    r2 = rot2 + rnd.gauss(0.0, math.sqrt(a1 * rot2**2 + a2 * trans**2))
    h = theta + r1
    p = [x + t * math.cos(h), y + t * math.sin(h), math.remainder(h + r2, 2 * math.pi)]
    return [list(p) for _ in range(n)]
