import math

import numpy as np


def levenberg_marquardt(poses, edges, lam0, trials):
    """Levenberg-Marquardt on a pose graph, pose 0 fixed; returns the poses seen from pose 0.

    poses: n poses (x, y, theta), metres and radians, in the world frame (2 <= n <= 160).
    edges: (i, j, z, omega): pose j measured from pose i as z = (dx, dy, dtheta), 3x3 omega.
    lam0: the first damping lambda (1e-6 to 1e4); trials: how many linear solves (0 to 15).
    Each trial solves (H + lam * diag(H)) delta = -b for poses 1..n-1, computes the gain ratio
    rho = (chi2(x) - chi2(x + delta)) / (-2 b.delta - delta.H.delta), and then
    rho > 0: accept, lam *= max(1/3, 1 - (2 rho - 1)**3), nu = 2;
    otherwise: keep x, lam *= nu, nu *= 2 (nu starts at 2).
    Returns an n x 3 array: x_0^-1 (+) x_k, angles in (-pi, pi].
    """
    raise NotImplementedError("damp, solve, judge the step by its gain ratio, update lambda")
