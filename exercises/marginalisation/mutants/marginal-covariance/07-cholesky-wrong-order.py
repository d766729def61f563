# mistake: with H = L L^T, takes the covariance as L^-1 L^-T instead of L^-T L^-1
import numpy as np


def marginal_covariance(H, block):
    L = np.linalg.cholesky(np.array(H, dtype=float))
    Li = np.linalg.inv(L)
    S = Li @ Li.T
    a = list(block)
    return S[np.ix_(a, a)]
