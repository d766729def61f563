import math

import numpy as np


def gauss_newton(poses, edges, iterations):
    """Optimise a pose graph with `iterations` undamped Gauss-Newton steps, pose 0 held fixed.

    poses: list of n initial poses (x, y, theta), metres and radians.
    edges: list of (i, j, z, omega): pose j measured from pose i as z = (dx, dy, dtheta),
           omega its 3x3 information matrix.
    Returns an n x 3 array: every optimised pose seen from pose 0 (x0^-1 (+) xk), angles
    wrapped into (-pi, pi].
    """
    raise NotImplementedError("build H and b from every edge, solve for poses 1..n-1, update")
