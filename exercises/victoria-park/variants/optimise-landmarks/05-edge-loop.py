# method: a Python loop over the lines builds a dense H, np.linalg.solve per step
import math

import numpy as np


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def rot_t(theta):
    c, s = math.cos(theta), math.sin(theta)
    return np.array([[c, s], [-s, c]])


def odometry_error(xi, xj, z):
    """e = z^-1 (+) (xi^-1 (+) xj) and its Jacobians A (by xi) and B (by xj)."""
    rz, ri = rot_t(z[2]), rot_t(xi[2])
    d = xj[:2] - xi[:2]
    e = np.zeros(3)
    e[:2] = rz @ (ri @ d - z[:2])
    e[2] = wrap(xj[2] - xi[2] - z[2])
    ci, si = math.cos(xi[2]), math.sin(xi[2])
    d_ri = np.array([[-si, ci], [-ci, -si]])
    a, b = np.zeros((3, 3)), np.zeros((3, 3))
    a[:2, :2] = -rz @ ri
    a[:2, 2] = rz @ d_ri @ d
    a[2, 2] = -1.0
    b[:2, :2] = rz @ ri
    b[2, 2] = 1.0
    return e, a, b


def landmark_error(x, tree, z):
    """e = R^T (l - t) - z and its Jacobians A (2x3, by the pose) and B (2x2, by l)."""
    rt = rot_t(x[2])
    h = rt @ (tree - x[:2])
    a = np.zeros((2, 3))
    a[:, :2] = -rt
    a[:, 2] = [h[1], -h[0]]
    return h - z, a, rt


def optimise_landmarks(text, iterations):
    odo, obs = [], []
    for line in text.splitlines():
        f = line.split()
        if not f:
            continue
        if f[0] == "ODOMETRY":
            c = [float(v) for v in f[6:12]]
            cov = np.array([[c[0], c[1], c[2]], [c[1], c[3], c[4]], [c[2], c[4], c[5]]])
            odo.append((int(f[1]), int(f[2]), np.array([float(v) for v in f[3:6]]), cov))
        elif f[0] == "LANDMARK":
            c = [float(v) for v in f[5:8]]
            cov = np.array([[c[0], c[1]], [c[1], c[2]]])
            obs.append((int(f[1]), int(f[2]), np.array([float(f[3]), float(f[4])]), cov))
    pose_ids = sorted({o[0] for o in odo} | {o[1] for o in odo} | {o[0] for o in obs})
    tree_ids = sorted({o[1] for o in obs})
    pk = {p: k for k, p in enumerate(pose_ids)}
    lk = {p: k for k, p in enumerate(tree_ids)}
    n, m = len(pose_ids), len(tree_ids)

    # initial guess: dead reckoning, then each tree at its first sighting
    x = np.zeros((n, 3))
    for i, j, z, _ in odo:
        xi = x[pk[i]]
        x[pk[j], :2] = xi[:2] + rot_t(xi[2]).T @ z[:2]
        x[pk[j], 2] = wrap(xi[2] + z[2])
    trees = np.zeros((m, 2))
    placed = set()
    for i, tree, z, _ in obs:
        if tree not in placed:
            xi = x[pk[i]]
            trees[lk[tree]] = xi[:2] + rot_t(xi[2]).T @ z
            placed.add(tree)

    odo_info = [np.linalg.inv(o[3]) for o in odo]
    obs_info = [np.linalg.inv(o[3]) for o in obs]
    size = 3 * n + 2 * m
    for _ in range(int(iterations)):
        h = np.zeros((size, size))
        b = np.zeros(size)
        for (i, j, z, _), om in zip(odo, odo_info, strict=True):
            a_, b_ = 3 * pk[i], 3 * pk[j]
            e, ja, jb = odometry_error(x[pk[i]], x[pk[j]], z)
            h[a_ : a_ + 3, a_ : a_ + 3] += ja.T @ om @ ja
            h[a_ : a_ + 3, b_ : b_ + 3] += ja.T @ om @ jb
            h[b_ : b_ + 3, a_ : a_ + 3] += jb.T @ om @ ja
            h[b_ : b_ + 3, b_ : b_ + 3] += jb.T @ om @ jb
            b[a_ : a_ + 3] += ja.T @ om @ e
            b[b_ : b_ + 3] += jb.T @ om @ e
        for (i, tree, z, _), om in zip(obs, obs_info, strict=True):
            a_, b_ = 3 * pk[i], 3 * n + 2 * lk[tree]
            e, ja, jb = landmark_error(x[pk[i]], trees[lk[tree]], z)
            h[a_ : a_ + 3, a_ : a_ + 3] += ja.T @ om @ ja
            h[a_ : a_ + 3, b_ : b_ + 2] += ja.T @ om @ jb
            h[b_ : b_ + 2, a_ : a_ + 3] += jb.T @ om @ ja
            h[b_ : b_ + 2, b_ : b_ + 2] += jb.T @ om @ jb
            b[a_ : a_ + 3] += ja.T @ om @ e
            b[b_ : b_ + 2] += jb.T @ om @ e
        step = np.linalg.solve(h[3:, 3:], -b[3:])
        x[1:] += step[: 3 * (n - 1)].reshape(-1, 3)
        x[:, 2] = [wrap(t) for t in x[:, 2]]
        trees += step[3 * (n - 1) :].reshape(-1, 2)

    # everything seen from pose 0 (which never moved from the origin, but say it anyway)
    r0 = rot_t(x[0, 2])
    out = []
    for k in range(n):
        p = r0 @ (x[k, :2] - x[0, :2])
        out += [p[0], p[1], wrap(x[k, 2] - x[0, 2])]
    for k in range(m):
        out += list(r0 @ (trees[k] - x[0, :2]))
    return np.array(out)
