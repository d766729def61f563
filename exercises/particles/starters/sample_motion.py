import math

import numpy as np


def sample_motion(pose, u, alphas, n, seed):
    """n poses drawn from the odometry motion model.

    pose: (x, y, theta) in metres and radians.
    u: (rot1, trans, rot2): turn, drive straight, turn (radians, metres, radians).
    alphas: (a1, a2, a3, a4): variances of the Gaussian noise on each control are
        a1*rot1**2 + a2*trans**2, a3*trans**2 + a4*(rot1**2 + rot2**2), a1*rot2**2 + a2*trans**2.
    n: number of samples; seed: draw all randomness from np.random.default_rng(seed).
    Returns an n x 3 array of poses, headings wrapped into (-pi, pi].
    """
    raise NotImplementedError("perturb each control with its own noise, then move every sample")
