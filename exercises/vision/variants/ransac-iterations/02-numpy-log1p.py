# method: numpy.log1p for log(1 - x), numpy.ceil, returned as a float
import numpy as np


def ransac_iterations(w, s, p):
    return np.ceil(np.log1p(-p) / np.log1p(-np.power(w, s)))
