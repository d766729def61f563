import math

import numpy as np


def optimise_landmarks(text, iterations):
    """Optimise a landmark pose graph given in GTSAM's ODOMETRY / LANDMARK text format.

    text: the file's content. ODOMETRY i j dx dy dtheta c11 c12 c13 c22 c23 c33 (covariance),
          LANDMARK i l x y c11 c12 c22 (landmark l seen from pose i, robot frame, covariance).
    iterations: undamped Gauss-Newton steps, pose 0 (smallest id) held fixed.
    Returns a flat array of 3n + 2m numbers: every pose (x, y, theta) seen from pose 0, by
    increasing id, then every landmark (x, y) seen from pose 0, by increasing id.
    """
    raise NotImplementedError("read, chain the initial guess, then Gauss-Newton over both factors")
