import numpy as np


def essential_matrix(t, R):
    tx, ty, tz = t
    t_cross = np.array([[0, -tz, ty],
                        [tz, 0, -tx],
                        [-ty, tx, 0]])
    return t_cross @ np.array(R)
