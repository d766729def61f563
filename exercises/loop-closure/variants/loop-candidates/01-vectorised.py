# method: every searched pose at once with numpy (stacked Jacobians, einsum), scipy chi2.ppf
import numpy as np
from scipy.stats import chi2


def loop_candidates(poses, marginals, cross, gap, confidence):
    x = np.asarray(poses, dtype=float)
    m = np.asarray(marginals, dtype=float)
    c = np.asarray(cross, dtype=float)
    k = len(x) - 1
    idx = np.arange(0, max(k - int(gap) + 1, 0))
    if len(idx) == 0:
        return []
    xi = x[idx]
    cs, sn = np.cos(xi[:, 2]), np.sin(xi[:, 2])
    dx, dy = x[k, 0] - xi[:, 0], x[k, 1] - xi[:, 1]
    n = len(idx)
    j = np.zeros((n, 2, 6))
    j[:, 0, 0], j[:, 0, 1], j[:, 0, 2] = -cs, -sn, -sn * dx + cs * dy
    j[:, 1, 0], j[:, 1, 1], j[:, 1, 2] = sn, -cs, -cs * dx - sn * dy
    j[:, 0, 3], j[:, 0, 4] = cs, sn
    j[:, 1, 3], j[:, 1, 4] = -sn, cs
    joint = np.zeros((n, 6, 6))
    joint[:, :3, :3] = m[idx]
    joint[:, :3, 3:] = c[idx]
    joint[:, 3:, :3] = np.transpose(c[idx], (0, 2, 1))
    joint[:, 3:, 3:] = m[k]
    s = np.einsum("nab,nbc,ndc->nad", j, joint, j)
    r = np.stack([cs * dx + sn * dy, -sn * dx + cs * dy], axis=1)
    d2 = np.einsum("na,na->n", r, np.linalg.solve(s, r[:, :, None])[:, :, 0])
    return idx[d2 <= chi2.ppf(confidence, 2)].tolist()
