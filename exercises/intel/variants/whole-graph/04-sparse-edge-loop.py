# method: one edge at a time in Python; H from (row, column, value) triplets, scipy.sparse + spsolve
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
    # e_xy = Rz' Ri' (t_j - t_i) - Rz' t_z and Rz' Ri' is the rotation by -(theta_i + theta_z)
    c, s = math.cos(xi[2] + z[2]), math.sin(xi[2] + z[2])
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    A = np.array([[-c, -s, -s * dx + c * dy], [s, -c, -c * dx - s * dy], [0.0, 0.0, -1.0]])
    B = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]])
    return A, B


def chi2(poses, edges):
    total = 0.0
    for i, j, z, omega in edges:
        e = edge_error(poses[i], poses[j], z)
        total += float(e @ omega @ e)
    return total


def gauss_newton(poses, edges, iterations):
    """Undamped Gauss-Newton, pose 0 fixed. H is sparse (a 3x3 block per pose and one per
    edge's pair of poses), so it is assembled from (row, column, value) triplets and solved
    with scipy's sparse LU, which orders the columns (COLAMD) to keep the fill small."""
    x = np.array(poses, dtype=float)
    n = len(x)
    index = [
        np.array([3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2])
        for i, j, _z, _O in edges
    ]  # the rows and columns of each edge's two poses
    rows = np.concatenate([np.repeat(idx, 6) for idx in index])  # each 6 x 6 block J'OJ
    cols = np.concatenate([np.tile(idx, 6) for idx in index])  # ... row by row
    keep = (rows >= 3) & (cols >= 3)  # pose 0 is held fixed: drop its rows and columns
    for _ in range(iterations):
        vals = []
        b = np.zeros(3 * n)
        for (i, j, z, O), idx in zip(edges, index):
            e = edge_error(x[i], x[j], z)
            A, B = edge_jacobians(x[i], x[j], z)
            J = np.hstack([A, B])  # the error's Jacobian with respect to (x_i, x_j): 3 x 6
            JtO = J.T @ O
            vals.append((JtO @ J).ravel())
            b[idx] += JtO @ e
        vals = np.concatenate(vals)
        H = coo_matrix(
            (vals[keep], (rows[keep] - 3, cols[keep] - 3)), shape=(3 * n - 3, 3 * n - 3)
        ).tocsc()  # duplicates are summed
        dx = spsolve(H, -b[3:])
        x[1:] += dx.reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    return x


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
    poses = [vertices[k] for k in range(len(vertices))]
    return poses, edges


def intel_chi2(text, iterations):
    poses, edges = read_g2o(text)
    return chi2(gauss_newton(poses, edges, iterations), edges)
