# method: the gate itself from scipy.stats.chi2.ppf with 2k degrees of freedom, and d² by a Cholesky whitening
import numpy as np
from scipy.stats import chi2


def joint_compatible(H, P, R, nu, confidence):
    H, P, R, nu = (np.asarray(a, dtype=float) for a in (H, P, R, nu))
    k = len(nu) // 2
    S = H @ P @ H.T + np.kron(np.eye(k), R)
    w = np.linalg.solve(np.linalg.cholesky(S), nu)
    return bool(w @ w < chi2.ppf(confidence, 2 * k))
