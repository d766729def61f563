# mistake: multiplies by the covariance (nu^T S nu) instead of its inverse
import numpy as np


def mahalanobis(nu0, nu1, s00, s11):
    nu = np.array([nu0, nu1])
    S = np.diag([s00, s11])
    return float(nu @ S @ nu)
