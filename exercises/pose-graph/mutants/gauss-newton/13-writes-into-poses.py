# mistake: adds each step to the caller's `poses` (poses[k] = ...) and returns them seen from pose 0
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
    n = len(poses)
    for _ in range(iterations):
        H = np.zeros((3 * n, 3 * n))
        b = np.zeros(3 * n)
        for i, j, z, omega in edges:
            O = np.array(omega, dtype=float)
            e = np.array(between(z, between(poses[i], poses[j])))
            A, B = jacobians(poses[i], poses[j], z)
            si, sj = slice(3 * i, 3 * i + 3), slice(3 * j, 3 * j + 3)
            H[si, si] += A.T @ O @ A
            H[si, sj] += A.T @ O @ B
            H[sj, si] += B.T @ O @ A
            H[sj, sj] += B.T @ O @ B
            b[si] += A.T @ O @ e
            b[sj] += B.T @ O @ e
        dx = np.linalg.solve(H[3:, 3:], -b[3:]).reshape(-1, 3)
        for k in range(1, n):
            x, y, t = poses[k]
            poses[k] = [x + dx[k - 1, 0], y + dx[k - 1, 1], wrap(t + dx[k - 1, 2])]
    return np.array([between(poses[0], p) for p in poses])
