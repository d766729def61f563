# mistake: adds the steps in place to np.asarray(poses, dtype=float), which is the caller's own array when poses is a float array
import math

import numpy as np


def wrap(a):
    r = math.remainder(a, 2 * math.pi)
    return math.pi if r == -math.pi else r


def between(a, b):
    dx, dy = b[0] - a[0], b[1] - a[1]
    c, s = math.cos(a[2]), math.sin(a[2])
    return [c * dx + s * dy, -s * dx + c * dy, wrap(b[2] - a[2])]


def jacobians(xi, xj, z):
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


def gauss_newton(poses, edges, iterations):
    x = np.asarray(poses, dtype=float)
    n = len(x)
    for _ in range(iterations):
        H = np.zeros((3 * n, 3 * n))
        b = np.zeros(3 * n)
        for i, j, z, omega in edges:
            O = np.asarray(omega, dtype=float)
            e = np.array(between(z, between(x[i], x[j])))
            A, B = jacobians(x[i], x[j], z)
            si, sj = slice(3 * i, 3 * i + 3), slice(3 * j, 3 * j + 3)
            H[si, si] += A.T @ O @ A
            H[si, sj] += A.T @ O @ B
            H[sj, si] += B.T @ O @ A
            H[sj, sj] += B.T @ O @ B
            b[si] += A.T @ O @ e
            b[sj] += B.T @ O @ e
        x[1:] += np.linalg.solve(H[3:, 3:], -b[3:]).reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
    return np.array([between(x[0], p) for p in x])
