# method: numpy.cross of t with each column of R (cross with R^T's rows, transpose back)
import numpy as np


def essential_matrix(t, R):
    return np.cross(t, np.asarray(R).T).T
