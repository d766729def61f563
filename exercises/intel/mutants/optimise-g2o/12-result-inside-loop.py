# mistake: converts the poses to pose 0's frame inside the iteration loop, so with iterations = 0 there is no result to return
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


def gauss_newton(poses, edges, iterations):
    x = np.array(poses, dtype=float)
    n = len(x)
    for _ in range(iterations):
        H = np.zeros((3 * n, 3 * n))
        b = np.zeros(3 * n)
        for i, j, z, omega in edges:
            O = np.array(omega, dtype=float)
            e = edge_error(x[i], x[j], z)
            A, B = edge_jacobians(x[i], x[j], z)
            si, sj = slice(3 * i, 3 * i + 3), slice(3 * j, 3 * j + 3)
            H[si, si] += A.T @ O @ A
            H[si, sj] += A.T @ O @ B
            H[sj, si] += B.T @ O @ A
            H[sj, sj] += B.T @ O @ B
            b[si] += A.T @ O @ e
            b[sj] += B.T @ O @ e
        dx = np.linalg.solve(H[3:, 3:], -b[3:])
        x[1:] += dx.reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
        relative = np.array([between(x[0], p) for p in x])
    return relative


def optimise_g2o(text, iterations):
    vertices, edges = {}, []
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "VERTEX_SE2":
            vertices[int(f[1])] = [float(v) for v in f[2:5]]
        elif f[0] == "EDGE_SE2":
            a, b, c, d, e, g = (float(v) for v in f[6:12])
            omega = [[a, b, c], [b, d, e], [c, e, g]]
            edges.append((int(f[1]), int(f[2]), [float(v) for v in f[3:6]], omega))
    poses = [vertices[k] for k in range(len(vertices))]
    return gauss_newton(poses, edges, iterations)
