# method: numpy.einsum over both indices at once, returning a numpy scalar
import numpy as np


def epipolar_residual(E, x, x2):
    return np.einsum("i,ik,k->", x2, E, x)
