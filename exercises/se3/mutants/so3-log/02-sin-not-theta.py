# mistake: returns the antisymmetric part sin(theta) n as the rotation vector
import numpy as np


def so3_log(R):
    R = np.array(R, dtype=float)
    return 0.5 * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
