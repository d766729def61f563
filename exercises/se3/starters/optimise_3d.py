import math

import numpy as np


def optimise_3d(text, iterations):
    """Optimise the 3-D pose graph of EDGE3 lines with Gauss-Newton, pose 0 fixed.

    text: EDGE3 i j x y z roll pitch yaw s11 s12 ... s66 lines (R = Rz(yaw) Ry(pitch) Rx(roll),
          the translation in pose i's frame, the upper triangle of the square-root information S).
    iterations: the number of Gauss-Newton steps, from the composed odometry.
    Returns an n x 3 array: the optimised position of every pose seen from pose 0 (metres).
    """
    raise NotImplementedError("parse, compose the odometry, then iterate x <- x Exp(delta)")
