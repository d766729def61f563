# method: through the covariance: Sigma = H^-1, H' = inv(Sigma_aa), b' = H' (Sigma b)_a (the marginal mean kept)
import numpy as np


def marginalise(H, b, keep):
    sigma = np.linalg.inv(np.array(H, dtype=float))
    mean = sigma @ np.array(b, dtype=float)
    a = list(keep)
    h_new = np.linalg.inv(sigma[np.ix_(a, a)])
    return np.c_[h_new, h_new @ mean[a]]
