# method: one edge at a time in Python: the 3x6 Jacobian [A B] added into a dense H with np.ix_
import math

import numpy as np


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


def gauss_newton(poses, edges, iterations):
    x = np.array(poses, dtype=float)
    n = len(x)
    omegas = [np.array(omega, dtype=float) for *_, omega in edges]
    for _ in range(iterations):
        H = np.zeros((3 * n, 3 * n))
        b = np.zeros(3 * n)
        for (i, j, z, _omega), O in zip(edges, omegas):
            e = edge_error(x[i], x[j], z)
            A, B = edge_jacobians(x[i], x[j], z)
            J = np.hstack([A, B])  # the error's Jacobian with respect to (x_i, x_j): 3 x 6
            JtO = J.T @ O
            rows = [3 * i, 3 * i + 1, 3 * i + 2, 3 * j, 3 * j + 1, 3 * j + 2]
            H[np.ix_(rows, rows)] += JtO @ J  # the blocks A'OA, A'OB, B'OA, B'OB at once
            b[rows] += JtO @ e
        dx = np.linalg.solve(H[3:, 3:], -b[3:])
        x[1:] += dx.reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    return np.array([between(x[0], p) for p in x])
