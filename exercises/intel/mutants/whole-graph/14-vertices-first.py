# mistake: reads VERTEX lines until the first EDGE line and edges after it, assuming the vertices come first
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
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    cz, sz = math.cos(z[2]), math.sin(z[2])
    rz_t = np.array([[cz, sz], [-sz, cz]])
    ri_t = np.array([[ci, si], [-si, ci]])
    d_ri_t = np.array([[-si, ci], [-ci, -si]])
    d = np.array([xj[0] - xi[0], xj[1] - xi[1]])
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    A[:2, :2] = -rz_t @ ri_t
    A[:2, 2] = rz_t @ d_ri_t @ d
    A[2, 2] = -1.0
    B[:2, :2] = rz_t @ ri_t
    B[2, 2] = 1.0
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
    block = np.arange(3)
    rr = np.repeat(block, 3)  # row offsets of a 3x3 block, row by row
    cc = np.tile(block, 3)  # column offsets
    for _ in range(iterations):
        rows, cols, vals = [], [], []
        b = np.zeros(3 * n)
        for i, j, z, O in edges:
            e = edge_error(x[i], x[j], z)
            A, B = edge_jacobians(x[i], x[j], z)
            for (p, P), (q, Q) in (((i, A), (i, A)), ((i, A), (j, B)),
                                   ((j, B), (i, A)), ((j, B), (j, B))):
                rows.append(3 * p + rr)
                cols.append(3 * q + cc)
                vals.append((P.T @ O @ Q).ravel())
            b[3 * i:3 * i + 3] += A.T @ O @ e
            b[3 * j:3 * j + 3] += B.T @ O @ e
        rows, cols, vals = np.concatenate(rows), np.concatenate(cols), np.concatenate(vals)
        keep = (rows >= 3) & (cols >= 3)  # pose 0 is held fixed: drop its rows and columns
        H = coo_matrix((vals[keep], (rows[keep] - 3, cols[keep] - 3)),
                       shape=(3 * n - 3, 3 * n - 3)).tocsc()  # duplicates are summed
        dx = spsolve(H, -b[3:])
        x[1:] += dx.reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    return x


def read_g2o(text):
    vertices, edges = {}, []
    seen_edge = False
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "EDGE_SE2":
            seen_edge = True
        if f[0] == "VERTEX_SE2" and not seen_edge:
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
