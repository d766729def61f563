import math

import numpy as np


def landmark_jacobian(pose, landmark):
    """Jacobian of e = R(theta)^T (l - t) - z with respect to the pose and the landmark.

    pose: (x, y, theta), metres and radians; landmark: (lx, ly), metres.
    Returns a 2x5 array [A | B]: A = de/d(x, y, theta) (2x3), B = de/d(lx, ly) (2x2).
    """
    raise NotImplementedError("differentiate h = R(theta)^T (l - t) by t, theta and l")
