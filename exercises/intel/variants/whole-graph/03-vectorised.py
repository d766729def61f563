# method: all edges at once in numpy arrays (errors, Jacobians, blocks added with np.add.at); headings never re-wrapped
import numpy as np


def read_g2o(text):
    vertices, rows = {}, []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "VERTEX_SE2":
            vertices[int(f[1])] = [float(v) for v in f[2:5]]
        elif f and f[0] == "EDGE_SE2":
            rows.append([float(v) for v in f[1:12]])
    x = np.array([vertices[k] for k in range(len(vertices))], dtype=float)
    r = np.array(rows, dtype=float).reshape(-1, 11)
    i, j, z = r[:, 0].astype(int), r[:, 1].astype(int), r[:, 2:5]
    a, b, c, d, e, g = r[:, 5:11].T
    om = np.stack([np.stack([a, b, c], 1), np.stack([b, d, e], 1), np.stack([c, e, g], 1)], 1)
    return x, i, j, z, om


def errors(x, i, j, z):
    """Errors (m x 3) and Jacobians A, B (m x 3 x 3) of all edges."""
    ti, tj = x[i, :2], x[j, :2]
    th = x[i, 2] + z[:, 2]  # R_z^T R_i^T = R(theta_i + theta_z)^T
    c, s = np.cos(th), np.sin(th)
    ci, si = np.cos(x[i, 2]), np.sin(x[i, 2])
    dx, dy = tj[:, 0] - ti[:, 0], tj[:, 1] - ti[:, 1]
    # e_xy = R_z^T (R_i^T (t_j - t_i) - t_z)
    lx, ly = ci * dx + si * dy - z[:, 0], -si * dx + ci * dy - z[:, 1]
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    ang = np.angle(np.exp(1j * (x[j, 2] - x[i, 2] - z[:, 2])))
    err = np.stack([cz * lx + sz * ly, -sz * lx + cz * ly, ang], 1)
    m = len(i)
    A = np.zeros((m, 3, 3))
    B = np.zeros((m, 3, 3))
    A[:, 0, 0], A[:, 0, 1], A[:, 1, 0], A[:, 1, 1] = -c, -s, s, -c
    B[:, 0, 0], B[:, 0, 1], B[:, 1, 0], B[:, 1, 1] = c, s, -s, c
    # d/dtheta_i of R(theta_i + theta_z)^T (t_j - t_i)
    A[:, 0, 2] = -s * dx + c * dy
    A[:, 1, 2] = -c * dx - s * dy
    A[:, 2, 2] = -1.0
    B[:, 2, 2] = 1.0
    return err, A, B


def intel_chi2(text, iterations):
    x, i, j, z, om = read_g2o(text)
    n = len(x)
    idx_i = 3 * i[:, None] + np.arange(3)
    idx_j = 3 * j[:, None] + np.arange(3)
    for _ in range(iterations):
        err, A, B = errors(x, i, j, z)
        AtO = np.transpose(A, (0, 2, 1)) @ om
        BtO = np.transpose(B, (0, 2, 1)) @ om
        H = np.zeros((3 * n, 3 * n))
        g = np.zeros(3 * n)
        for p, q, blocks in (
            (idx_i, idx_i, AtO @ A),
            (idx_i, idx_j, AtO @ B),
            (idx_j, idx_i, BtO @ A),
            (idx_j, idx_j, BtO @ B),
        ):
            np.add.at(H, (p[:, :, None], q[:, None, :]), blocks)
        np.add.at(g, idx_i, np.einsum("kab,kb->ka", AtO, err))
        np.add.at(g, idx_j, np.einsum("kab,kb->ka", BtO, err))
        x[1:] += np.linalg.solve(H[3:, 3:], -g[3:]).reshape(-1, 3)
    err, _, _ = errors(x, i, j, z)
    return float(np.einsum("ka,kab,kb->", err, om, err))
