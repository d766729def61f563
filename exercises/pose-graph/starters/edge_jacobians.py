import math

import numpy as np


def edge_jacobians(xi, xj, z):
    """Jacobians of e = z^-1 (+) (xi^-1 (+) xj) with respect to xi and xj.

    xi, xj: poses (x, y, theta); z: the measurement (dx, dy, dtheta).
    Returns a 3x6 array [A | B] with A = de/dxi (3x3) and B = de/dxj (3x3).
    """
    raise NotImplementedError("differentiate e_xy = Rz^T (Ri^T (tj - ti) - tz) and e_theta")
