# method: numpy, solve S x = nu and return nu . x (works for any S)
import numpy as np


def mahalanobis(nu0, nu1, s00, s11):
    nu = np.array([nu0, nu1])
    S = np.array([[s00, 0.0], [0.0, s11]])
    return nu @ np.linalg.solve(S, nu)
