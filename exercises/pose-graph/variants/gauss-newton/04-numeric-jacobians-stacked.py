# method: homogeneous matrices, Jacobians by central differences, stacked whitened least squares
import math

import numpy as np


def T(p):
    c, s = math.cos(p[2]), math.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0.0, 0.0, 1.0]])


def v(M):
    return np.array([M[0, 2], M[1, 2], math.atan2(M[1, 0], M[0, 0])])


def error(xi, xj, z):
    return v(np.linalg.inv(T(z)) @ np.linalg.inv(T(xi)) @ T(xj))


def numeric(f, p, h=1e-6):
    cols = []
    for k in range(3):
        d = np.zeros(3)
        d[k] = h
        diff = f(p + d) - f(p - d)
        diff[2] = math.remainder(diff[2], 2 * math.pi)
        cols.append(diff / (2 * h))
    return np.column_stack(cols)


def gauss_newton(poses, edges, iterations):
    x = np.array(poses, dtype=float)
    n = len(x)
    for _ in range(iterations):
        rows, rhs = [], []
        for i, j, z, omega in edges:
            L = np.linalg.cholesky(np.array(omega, dtype=float))  # omega = L L^T
            e = error(x[i], x[j], z)
            A = numeric(lambda p: error(p, x[j], z), x[i])
            B = numeric(lambda p: error(x[i], p, z), x[j])
            J = np.zeros((3, 3 * n))
            J[:, 3 * i : 3 * i + 3] = A
            J[:, 3 * j : 3 * j + 3] = B
            rows.append(L.T @ J)
            rhs.append(-(L.T @ e))
        J = np.vstack(rows)[:, 3:]
        step = np.linalg.lstsq(J, np.concatenate(rhs), rcond=None)[0]
        x[1:] += step.reshape(-1, 3)
        x[:, 2] = np.arctan2(np.sin(x[:, 2]), np.cos(x[:, 2]))
    out = [v(np.linalg.inv(T(x[0])) @ T(p)) for p in x]
    return np.array(out)
