import math

import numpy as np


def robust_optimise(text, kernel, k, iterations):
    """IRLS on a 2-D g2o pose graph with pose 0 fixed; returns the poses seen from pose 0.

    text: the whole g2o file (VERTEX_SE2 id x y theta; EDGE_SE2 i j dx dy dtheta + the upper
          triangle I11 I12 I13 I22 I23 I33 of the information matrix).
    kernel: "l2", "huber", "cauchy" or "dcs"; k: its width (boundary at s = k**2).
    iterations: the number of reweighted Gauss-Newton steps (0 or more).
    Loop closures (|i - j| != 1) get the weight w(s) of s = e^T Omega e at the current poses;
    odometry edges get 1. Returns an n x 3 array: x_0^-1 (+) x_k, angles in (-pi, pi].
    """
    raise NotImplementedError("reweight the loop closures, then take one Gauss-Newton step")
