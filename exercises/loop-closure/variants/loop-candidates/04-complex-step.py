# method: the Jacobian of r_xy by complex-step differentiation, a Cholesky solve, chi2.ppf
import cmath

import numpy as np
from scipy.linalg import cho_factor, cho_solve
from scipy.stats import chi2


def rel_xy(v):
    """r_xy of pose k (v[3:]) seen from pose i (v[:3]); works on complex numbers."""
    c, s = cmath.cos(v[2]), cmath.sin(v[2])
    dx, dy = v[3] - v[0], v[4] - v[1]
    return np.array([c * dx + s * dy, -s * dx + c * dy])


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    gate = chi2.ppf(confidence, df=2)
    h = 1e-30
    out = []
    for i in range(k - int(gap) + 1):
        v = np.concatenate([x[i], x[k]]).astype(complex)
        jac = np.zeros((2, 6))
        for a in range(6):
            step = v.copy()
            step[a] += 1j * h
            jac[:, a] = rel_xy(step).imag / h
        joint = np.vstack([np.hstack([m[i], c[i]]), np.hstack([c[i].T, m[k]])])
        s = jac @ joint @ jac.T
        r = rel_xy(v).real
        if float(r @ cho_solve(cho_factor(s), r)) <= gate:
            out.append(i)
    return out
