# method: homogeneous matrices for the error, H kept as a dict of 3x3 blocks, then a csr matrix
import math

import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.linalg import spsolve


def wrap(a):
    a = (a + math.pi) % (2 * math.pi) - math.pi
    return math.pi if a == -math.pi else a


def t2m(p):
    c, s = math.cos(p[2]), math.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0.0, 0.0, 1.0]])


def m2t(m):
    return np.array([m[0, 2], m[1, 2], math.atan2(m[1, 0], m[0, 0])])


def error(xi, xj, z):
    # e = t2v(Z^-1 Xi^-1 Xj) with homogeneous matrices
    return m2t(np.linalg.inv(t2m(z)) @ np.linalg.inv(t2m(xi)) @ t2m(xj))


def jacobians(xi, xj, z):
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    cz, sz = math.cos(z[2]), math.sin(z[2])
    rit = np.array([[ci, si], [-si, ci]])
    rzt = np.array([[cz, sz], [-sz, cz]])
    drit = np.array([[-si, ci], [-ci, -si]])
    t = np.array([xj[0] - xi[0], xj[1] - xi[1]])
    A = np.zeros((3, 3))
    B = np.zeros((3, 3))
    A[:2, :2] = -rzt @ rit
    A[:2, 2] = rzt @ drit @ t
    A[2, 2] = -1.0
    B[:2, :2] = rzt @ rit
    B[2, 2] = 1.0
    return A, B


def weight(kernel, s, k):
    if kernel == "huber":
        return 1.0 if s <= k * k else k / math.sqrt(s)
    if kernel == "cauchy":
        return k * k / (k * k + s)
    if kernel == "dcs":
        return min(1.0, 2 * k * k / (k * k + s)) ** 2
    return 1.0


def robust_optimise(text, kernel, k, iterations):
    verts, edges = {}, []
    for line in text.split("\n"):
        f = line.strip().split()
        if f and f[0] == "VERTEX_SE2":
            verts[int(f[1])] = [float(v) for v in f[2:5]]
        elif f and f[0] == "EDGE_SE2":
            u = [float(v) for v in f[6:12]]
            om = np.array([[u[0], u[1], u[2]], [u[1], u[3], u[4]], [u[2], u[4], u[5]]])
            edges.append((int(f[1]), int(f[2]), [float(v) for v in f[3:6]], om))
    n = len(verts)
    x = np.array([verts[i] for i in range(n)])
    for _ in range(iterations):
        blocks = {}  # (row pose, column pose) -> 3x3 block of H
        b = np.zeros((n, 3))
        for i, j, z, om in edges:
            e = error(x[i], x[j], z)
            w = weight(kernel, float(e @ om @ e), k) if abs(i - j) != 1 else 1.0
            A, B = jacobians(x[i], x[j], z)
            wom = w * om
            for p, jp in ((i, A), (j, B)):
                for q, jq in ((i, A), (j, B)):
                    blocks[p, q] = blocks.get((p, q), 0) + jp.T @ wom @ jq
            b[i] += A.T @ wom @ e
            b[j] += B.T @ wom @ e
        rows, cols, vals = [], [], []
        for (p, q), block in blocks.items():
            if p > 0 and q > 0:  # pose 0 is held fixed: its rows and columns are left out
                for r in range(3):
                    for c in range(3):
                        rows.append(3 * (p - 1) + r)
                        cols.append(3 * (q - 1) + c)
                        vals.append(block[r, c])
        H = csr_matrix((vals, (rows, cols)), shape=(3 * n - 3, 3 * n - 3))
        dx = spsolve(H, -b[1:].ravel())
        x[1:] += dx.reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    x0 = np.linalg.inv(t2m(x[0]))
    return np.array([m2t(x0 @ t2m(p)) for p in x])
