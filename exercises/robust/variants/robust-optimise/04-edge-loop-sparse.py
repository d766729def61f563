# method: a Python loop over the edges with math, H as a coo matrix solved by spsolve
import math

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve


def wrap(a):
    r = math.remainder(a, 2 * math.pi)
    return math.pi if r == -math.pi else r


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return [c * dx + s * dy, -s * dx + c * dy, wrap(b[2] - a[2])]


def edge_error(xi, xj, z):
    return np.array(between(z, between(xi, xj)))


def edge_jacobians(xi, xj, z):
    c, s = math.cos(xi[2] + z[2]), math.sin(xi[2] + z[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    A = np.array([[-c, -s, -s * dx + c * dy], [s, -c, -c * dx - s * dy], [0.0, 0.0, -1.0]])
    B = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return A, B


def robust_weights(kind, s, k):
    s = np.asarray(s, dtype=float).reshape(-1)
    k2 = k * k
    if kind == "l2":
        return np.ones(len(s))
    if kind == "huber":
        return np.where(s <= k2, 1.0, k / np.sqrt(np.maximum(s, k2)))
    if kind == "cauchy":
        return 1.0 / (1.0 + s / k2)
    return np.minimum(1.0, 2.0 * k2 / (k2 + s)) ** 2


def read_g2o(text):
    vertices, edges = {}, []
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "VERTEX_SE2":
            vertices[int(f[1])] = [float(v) for v in f[2:5]]
        elif f[0] == "EDGE_SE2":
            a, b, c, d, e, g = (float(v) for v in f[6:12])
            omega = np.array([[a, b, c], [b, d, e], [c, e, g]])
            edges.append((int(f[1]), int(f[2]), [float(v) for v in f[3:6]], omega))
    return [vertices[k] for k in range(len(vertices))], edges


def robust_optimise(text, kernel, k, iterations):
    poses, edges = read_g2o(text)
    x = np.array(poses, dtype=float)
    n = len(x)
    loop = np.array([abs(i - j) != 1 for i, j, _z, _om in edges])
    index = [np.r_[3 * i : 3 * i + 3, 3 * j : 3 * j + 3] for i, j, _z, _om in edges]
    rows = np.concatenate([np.repeat(idx, 6) for idx in index])
    cols = np.concatenate([np.tile(idx, 6) for idx in index])
    keep = (rows >= 3) & (cols >= 3)  # pose 0 is held fixed
    for _ in range(iterations):
        errors = [edge_error(x[i], x[j], z) for i, j, z, _om in edges]
        s = np.array([e @ om @ e for e, (_i, _j, _z, om) in zip(errors, edges, strict=True)])
        w = np.where(loop, robust_weights(kernel, s, k), 1.0)
        vals, b = [], np.zeros(3 * n)
        for (i, j, z, om), e, wk, idx in zip(edges, errors, w, index, strict=True):
            A, B = edge_jacobians(x[i], x[j], z)
            J = np.hstack([A, B])
            JtO = wk * (J.T @ om)
            vals.append((JtO @ J).ravel())
            b[idx] += JtO @ e
        vals = np.concatenate(vals)
        H = coo_matrix((vals[keep], (rows[keep] - 3, cols[keep] - 3)), shape=(3 * n - 3, 3 * n - 3))
        x[1:] += spsolve(H.tocsc(), -b[3:]).reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    return np.array([between(x[0], p) for p in x])
