# method: a Python loop over the edges adding 3x3 blocks into a dense H, np.linalg.solve
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


def chi2(x, edges):
    total = 0.0
    for i, j, z, omega in edges:
        e = edge_error(x[i], x[j], z)
        total += float(e @ np.array(omega, dtype=float) @ e)
    return total


def linear_system(x, edges):
    n = len(x)
    H = np.zeros((3 * n, 3 * n))
    b = np.zeros(3 * n)
    for i, j, z, omega in edges:
        om = np.array(omega, dtype=float)
        e = edge_error(x[i], x[j], z)
        A, B = edge_jacobians(x[i], x[j], z)
        si, sj = slice(3 * i, 3 * i + 3), slice(3 * j, 3 * j + 3)
        H[si, si] += A.T @ om @ A
        H[si, sj] += A.T @ om @ B
        H[sj, si] += B.T @ om @ A
        H[sj, sj] += B.T @ om @ B
        b[si] += A.T @ om @ e
        b[sj] += B.T @ om @ e
    return H[3:, 3:], b[3:]


def levenberg_marquardt(poses, edges, lam0, trials):
    x = np.array(poses, dtype=float)
    lam, nu = float(lam0), 2.0
    current = chi2(x, edges)
    for _ in range(trials):
        H, b = linear_system(x, edges)
        D = np.diag(np.diag(H))
        delta = np.linalg.solve(H + lam * D, -b)
        candidate = x.copy()
        candidate[1:] += delta.reshape(-1, 3)
        candidate[:, 2] = [wrap(t) for t in candidate[:, 2]]
        new = chi2(candidate, edges)
        predicted = -2.0 * (b @ delta) - delta @ H @ delta
        rho = (current - new) / predicted if predicted > 0 else -1.0
        if rho > 0:
            x, current = candidate, new
            lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            nu = 2.0
        else:
            lam *= nu
            nu *= 2.0
    return np.array([between(x[0], p) for p in x])
