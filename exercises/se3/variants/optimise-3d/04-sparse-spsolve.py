# method: every edge at once with numpy, H assembled as a scipy.sparse matrix and spsolve

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve


def hat(w):
    """[w]x for a stack of vectors (m, 3) -> (m, 3, 3)."""
    k = np.zeros((len(w), 3, 3))
    k[:, 0, 1], k[:, 0, 2], k[:, 1, 2] = -w[:, 2], w[:, 1], -w[:, 0]
    k[:, 1, 0], k[:, 2, 0], k[:, 2, 1] = w[:, 2], -w[:, 1], w[:, 0]
    return k


def coefficients(t):
    """sin t / t, (1 - cos t) / t^2, (t - sin t) / t^3, with series for small t."""
    small = t < 1e-4
    s = np.where(small, 1.0, t)
    a = np.where(small, 1 - t**2 / 6, np.sin(s) / s)
    b = np.where(small, 0.5 - t**2 / 24, (1 - np.cos(s)) / s**2)
    c = np.where(small, 1 / 6 - t**2 / 120, (s - np.sin(s)) / s**3)
    return a, b, c


def exp_so3(w):
    a, b, _ = coefficients(np.linalg.norm(w, axis=1))
    k = hat(w)
    return np.eye(3) + a[:, None, None] * k + b[:, None, None] * k @ k


def log_so3(R):
    """Rotation vectors of a stack of rotations (angles well below pi in a pose graph's errors)."""
    v = 0.5 * np.stack(
        [R[:, 2, 1] - R[:, 1, 2], R[:, 0, 2] - R[:, 2, 0], R[:, 1, 0] - R[:, 0, 1]], 1
    )
    s = np.linalg.norm(v, axis=1)
    c = (np.trace(R, axis1=1, axis2=2) - 1) / 2
    theta = np.arctan2(s, c)
    factor = np.where(theta < 1e-4, 1 + theta**2 / 6, theta / np.where(s > 0, s, 1.0))
    return factor[:, None] * v


def jr_inverse(w):
    t = np.linalg.norm(w, axis=1)
    small = t < 1e-4
    s = np.where(small, 1.0, t)
    d = np.where(small, 1 / 12, 1 / s**2 - (1 + np.cos(s)) / (2 * s * np.sin(s)))
    k = hat(w)
    return np.eye(3) + 0.5 * k + d[:, None, None] * k @ k


def exp_se3(xi):
    phi = xi[:, 3:]
    _, b, c = coefficients(np.linalg.norm(phi, axis=1))
    k = hat(phi)
    v = np.eye(3) + b[:, None, None] * k + c[:, None, None] * k @ k
    T = np.zeros((len(xi), 4, 4))
    T[:, :3, :3] = exp_so3(phi)
    T[:, :3, 3] = np.einsum("kij,kj->ki", v, xi[:, :3])
    T[:, 3, 3] = 1
    return T


def inverse(T):
    out = np.zeros_like(T)
    Rt = np.transpose(T[:, :3, :3], (0, 2, 1))
    out[:, :3, :3] = Rt
    out[:, :3, 3] = -np.einsum("kij,kj->ki", Rt, T[:, :3, 3])
    out[:, 3, 3] = 1
    return out


def adjoint(T):
    R = T[:, :3, :3]
    ad = np.zeros((len(T), 6, 6))
    ad[:, :3, :3] = R
    ad[:, :3, 3:] = hat(T[:, :3, 3]) @ R
    ad[:, 3:, 3:] = R
    return ad


def rpy(roll, pitch, yaw):
    def rot(axis, a):
        w = np.zeros((len(a), 3))
        w[:, axis] = a
        return exp_so3(w)

    return rot(2, yaw) @ rot(1, pitch) @ rot(0, roll)


def read(text):
    rows = [line.split() for line in text.splitlines()]
    rows = [f for f in rows if f and f[0] == "EDGE3"]
    i = np.array([int(f[1]) for f in rows])
    j = np.array([int(f[2]) for f in rows])
    v = np.array([[float(x) for x in f[3:30]] for f in rows])
    Z = np.zeros((len(rows), 4, 4))
    Z[:, :3, :3] = rpy(v[:, 3], v[:, 4], v[:, 5])
    Z[:, :3, 3] = v[:, :3]
    Z[:, 3, 3] = 1
    S = np.zeros((len(rows), 6, 6))
    r, c = np.triu_indices(6)
    S[:, r, c] = v[:, 6:]
    omega = np.transpose(S, (0, 2, 1)) @ S  # the numbers are the square-root information
    return i, j, Z, omega


def errors(X, i, j, Z):
    Y = inverse(X[i]) @ X[j]
    E = inverse(Z) @ Y
    phi = log_so3(E[:, :3, :3])
    e = np.concatenate([E[:, :3, 3], phi], axis=1)
    D = np.zeros((len(e), 6, 6))
    D[:, :3, :3] = E[:, :3, :3]
    D[:, 3:, 3:] = jr_inverse(phi)
    A = -D @ adjoint(inverse(Y))
    return e, A, D


def optimise_3d(text, iterations):
    i, j, Z, omega = read(text)
    n = int(max(i.max(), j.max())) + 1
    odometry = {(a, b): k for k, (a, b) in enumerate(zip(i, j, strict=True)) if b == a + 1}
    X = np.zeros((n, 4, 4))
    X[0] = np.eye(4)
    for k in range(1, n):
        X[k] = X[k - 1] @ Z[odometry[(k - 1, k)]]
    idx = np.arange(6)
    for _ in range(iterations):
        e, A, B = errors(X, i, j, Z)
        AtO = np.transpose(A, (0, 2, 1)) @ omega
        BtO = np.transpose(B, (0, 2, 1)) @ omega
        g = np.zeros(6 * n)
        np.add.at(g, 6 * i[:, None] + idx, np.einsum("kij,kj->ki", AtO, e))
        np.add.at(g, 6 * j[:, None] + idx, np.einsum("kij,kj->ki", BtO, e))
        rows, cols, vals = [], [], []
        for p, q, block in ((i, i, AtO @ A), (i, j, AtO @ B), (j, i, BtO @ A), (j, j, BtO @ B)):
            rows.append(np.repeat(6 * p[:, None] + idx, 6, axis=1).ravel())
            cols.append(np.tile(6 * q[:, None] + idx, 6).ravel())
            vals.append(block.ravel())
        H = coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(6 * n, 6 * n),
        ).tocsc()
        delta = np.zeros(6 * n)
        delta[6:] = spsolve(H[6:, 6:], -g[6:])
        X = X @ exp_se3(delta.reshape(n, 6))
    return (inverse(X[:1]) @ X)[:, :3, 3]
