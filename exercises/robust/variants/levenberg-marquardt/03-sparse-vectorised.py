# method: all edges at once with numpy, H as a scipy.sparse matrix solved by spsolve
import numpy as np
from scipy.sparse import coo_matrix, diags
from scipy.sparse.linalg import spsolve


def wrap(a):
    return np.arctan2(np.sin(a), np.cos(a))


def parts(edges):
    i = np.array([int(e[0]) for e in edges])
    j = np.array([int(e[1]) for e in edges])
    z = np.array([[float(v) for v in e[2]] for e in edges])
    om = np.array([np.array(e[3], dtype=float) for e in edges])
    return i, j, z, om


def errors(x, i, j, z):
    d = x[j, :2] - x[i, :2]
    a = x[i, 2] + z[:, 2]
    c, s = np.cos(x[i, 2]), np.sin(x[i, 2])
    local = np.stack([c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]], axis=1) - z[:, :2]
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    ex = cz * local[:, 0] + sz * local[:, 1]
    ey = -sz * local[:, 0] + cz * local[:, 1]
    return np.stack([ex, ey, wrap(x[j, 2] - a)], axis=1), d


def chi2(x, i, j, z, om):
    e, _ = errors(x, i, j, z)
    return float(np.einsum("ka,kab,kb->", e, om, e))


def system(x, i, j, z, om):
    n, m = len(x), len(i)
    e, d = errors(x, i, j, z)
    a = x[i, 2] + z[:, 2]
    c, s = np.cos(a), np.sin(a)
    # e_xy = R(a)^T d - R(z)^T t_z: d/dd = R(a)^T, d/dtheta_i = dR(a)^T/da d
    J = np.zeros((m, 3, 6))
    J[:, 0, 0], J[:, 0, 1], J[:, 1, 0], J[:, 1, 1] = -c, -s, s, -c
    J[:, 0, 2] = -s * d[:, 0] + c * d[:, 1]
    J[:, 1, 2] = -c * d[:, 0] - s * d[:, 1]
    J[:, 2, 2] = -1.0
    J[:, 0, 3], J[:, 0, 4], J[:, 1, 3], J[:, 1, 4] = c, s, -s, c
    J[:, 2, 5] = 1.0
    JtO = np.einsum("kai,kab->kib", J, om)
    blocks = np.einsum("kib,kbj->kij", JtO, J)
    idx = np.concatenate([3 * i[:, None] + np.arange(3), 3 * j[:, None] + np.arange(3)], axis=1)
    g = np.zeros(3 * n)
    np.add.at(g, idx, np.einsum("kib,kb->ki", JtO, e))
    rows = np.repeat(idx, 6, axis=1).ravel()
    cols = np.tile(idx, (1, 6)).ravel()
    H = coo_matrix((blocks.ravel(), (rows, cols)), shape=(3 * n, 3 * n)).tocsc()
    return H[3:, 3:], g[3:]


def levenberg_marquardt(poses, edges, lam0, trials):
    x = np.array(poses, dtype=float)
    i, j, z, om = parts(edges)
    lam, nu = float(lam0), 2.0
    current = chi2(x, i, j, z, om)
    for _ in range(int(trials)):
        H, b = system(x, i, j, z, om)
        delta = spsolve((H + diags(lam * H.diagonal())).tocsc(), -b)
        candidate = x.copy()
        candidate[1:] += delta.reshape(-1, 3)
        new = chi2(candidate, i, j, z, om)
        predicted = -2.0 * float(b @ delta) - float(delta @ (H @ delta))
        rho = (current - new) / predicted if predicted > 0 else -1.0
        if rho > 0:
            x, current = candidate, new
            lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            nu = 2.0
        else:
            lam *= nu
            nu *= 2.0
    d = x[:, :2] - x[0, :2]
    c, s = np.cos(x[0, 2]), np.sin(x[0, 2])
    out = np.stack(
        [c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1], wrap(x[:, 2] - x[0, 2])], axis=1
    )
    out[out[:, 2] == -np.pi, 2] = np.pi
    return out
