# method: Box-Muller from uniform numbers, and the motion as complex numbers (pose (+) turn (+) drive (+) turn)
import cmath
import math

import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    rng = np.random.default_rng(seed)
    a1, a2, a3, a4 = alphas
    rot1, trans, rot2 = u
    sd = np.array([
        math.sqrt(a1 * rot1**2 + a2 * trans**2),
        math.sqrt(a3 * trans**2 + a4 * (rot1**2 + rot2**2)),
        math.sqrt(a1 * rot2**2 + a2 * trans**2),
    ])
    u1 = 1.0 - rng.random((n, 3))  # in (0, 1]: the logarithm is finite
    u2 = rng.random((n, 3))
    normal = np.sqrt(-2.0 * np.log(u1)) * np.cos(2 * np.pi * u2)
    noisy = np.array(u, dtype=float) + normal * sd
    out = np.empty((n, 3))
    start = complex(pose[0], pose[1])
    for k in range(n):
        r1, t, r2 = noisy[k]
        facing = cmath.exp(1j * (pose[2] + r1))
        p = start + t * facing
        out[k] = (p.real, p.imag, cmath.phase(facing * cmath.exp(1j * r2)))
    return out
