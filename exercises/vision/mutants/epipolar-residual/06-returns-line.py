# mistake: returns E x (the epipolar line in image 2) and never takes the dot product with x'
import numpy as np


def epipolar_residual(E, x, x2):
    return np.array(E) @ np.array(x)
