# method: explicit inverse with np.linalg.inv, nu^T S^-1 nu as a 1x1 matrix product
import numpy as np


def mahalanobis(nu0, nu1, s00, s11):
    nu = np.array([[nu0], [nu1]])
    S_inv = np.linalg.inv(np.diag([s00, s11]))
    return (nu.T @ S_inv @ nu)[0, 0]
