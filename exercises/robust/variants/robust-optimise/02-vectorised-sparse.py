# method: errors, Jacobians and weights of all edges at once with numpy arrays; H as a csc matrix
import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import spsolve


def parse(text):
    rows = [line.split() for line in text.splitlines()]
    verts = sorted(
        (int(r[1]), [float(v) for v in r[2:5]]) for r in rows if r and r[0] == "VERTEX_SE2"
    )
    edges = np.array([[float(v) for v in r[1:12]] for r in rows if r and r[0] == "EDGE_SE2"])
    return np.array([p for _, p in verts]), edges.reshape(-1, 11)


def wrap(a):
    a = np.arctan2(np.sin(a), np.cos(a))
    return np.where(a <= -np.pi, np.pi, a)


def robust_optimise(text, kernel, k, iterations):
    x, ed = parse(text)
    n = len(x)
    i, j = ed[:, 0].astype(int), ed[:, 1].astype(int)
    z = ed[:, 2:5]
    u = ed[:, 5:11]
    om = np.stack([u[:, [0, 1, 2]], u[:, [1, 3, 4]], u[:, [2, 4, 5]]], axis=1)
    loop = np.abs(i - j) != 1
    idx = np.concatenate([3 * i[:, None] + np.arange(3), 3 * j[:, None] + np.arange(3)], axis=1)
    rows = np.repeat(idx, 6, axis=1).ravel()
    cols = np.tile(idx, (1, 6)).ravel()
    m = len(i)
    for _ in range(iterations):
        d = x[j, :2] - x[i, :2]
        th = x[i, 2] + z[:, 2]
        c, s = np.cos(th), np.sin(th)
        cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
        # R(theta_i + theta_z)^T d - R(theta_z)^T t_z
        e = np.stack(
            [
                c * d[:, 0] + s * d[:, 1] - (cz * z[:, 0] + sz * z[:, 1]),
                -s * d[:, 0] + c * d[:, 1] - (-sz * z[:, 0] + cz * z[:, 1]),
                wrap(x[j, 2] - x[i, 2] - z[:, 2]),
            ],
            axis=1,
        )
        sq = np.einsum("ka,kab,kb->k", e, om, e)
        k2 = k * k
        if kernel == "huber":
            w = np.minimum(1.0, k / np.sqrt(np.maximum(sq, 1e-300)))
        elif kernel == "cauchy":
            w = 1.0 / (1.0 + sq / k2)
        elif kernel == "dcs":
            w = np.minimum(1.0, 2 * k2 / (k2 + sq)) ** 2
        else:
            w = np.ones(m)
        w = np.where(loop, w, 1.0)
        J = np.zeros((m, 3, 6))
        J[:, 0, 0], J[:, 0, 1], J[:, 1, 0], J[:, 1, 1] = -c, -s, s, -c
        J[:, 0, 2] = -s * d[:, 0] + c * d[:, 1]
        J[:, 1, 2] = -c * d[:, 0] - s * d[:, 1]
        J[:, 2, 2] = -1.0
        J[:, 0, 3], J[:, 0, 4], J[:, 1, 3], J[:, 1, 4] = c, s, -s, c
        J[:, 2, 5] = 1.0
        JtO = np.einsum("kai,kab->kib", J, om * w[:, None, None])
        blocks = np.einsum("kib,kbj->kij", JtO, J)
        g = np.zeros(3 * n)
        np.add.at(g, idx, np.einsum("kib,kb->ki", JtO, e))
        H = sp.coo_matrix((blocks.ravel(), (rows, cols)), shape=(3 * n, 3 * n)).tocsc()[3:, 3:]
        x = x.copy()
        x[1:] += spsolve(H, -g[3:]).reshape(-1, 3)
        x[:, 2] = wrap(x[:, 2])
    c0, s0 = np.cos(x[0, 2]), np.sin(x[0, 2])
    dd = x[:, :2] - x[0, :2]
    return np.stack(
        [c0 * dd[:, 0] + s0 * dd[:, 1], -s0 * dd[:, 0] + c0 * dd[:, 1], wrap(x[:, 2] - x[0, 2])],
        axis=1,
    )
