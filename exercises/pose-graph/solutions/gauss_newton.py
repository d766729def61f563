import numpy as np


def wrap(a):
    """Angles (an array) wrapped into (-pi, pi]."""
    return np.pi - np.remainder(np.pi - a, 2 * np.pi)


def linearise(x, i, j, offset, J):
    """edge_error and edge_jacobians of every edge at once: fill J (m x 3 x 7), each edge's
    [A | B | e], at the poses x.

    e_xy = R_z' (R_i' (t_j - t_i) - t_z) = R(theta_i + theta_z)' (t_j - t_i) - R_z' t_z, and
    e_theta = theta_j - theta_i - theta_z (wrapped): `offset` holds (R_z' t_z, theta_z). B is
    R(theta_i + theta_z)' with a 1 in the corner, A is -B but for its heading column
    d e_xy / d theta_i = (u_y, -u_x), where u = R(theta_i + theta_z)' (t_j - t_i).
    """
    A, B, e = J[:, :, 0:3], J[:, :, 3:6], J[:, :, 6]  # views: writing them fills J
    xi = x[i]
    angle = xi[:, 2] + offset[:, 2]
    c, s = np.cos(angle), np.sin(angle)
    B[:, 0, 0] = B[:, 1, 1] = c
    B[:, 0, 1] = s
    B[:, 1, 0] = -s
    u = (B @ (x[j] - xi)[:, :, None])[:, :, 0]  # (u_x, u_y, theta_j - theta_i)
    e[:] = u - offset
    e[:, 2] = wrap(e[:, 2])
    A[:, :2, :2] = -B[:, :2, :2]
    A[:, 0, 2], A[:, 1, 2] = u[:, 1], -u[:, 0]


def gauss_newton(poses, edges, iterations):
    x = np.array(poses, dtype=float).reshape(-1, 3)  # a copy: the arguments stay as they are
    n, m = len(x), len(edges)
    i = np.array([edge[0] for edge in edges], dtype=int)
    j = np.array([edge[1] for edge in edges], dtype=int)
    z = np.array([edge[2] for edge in edges], dtype=float).reshape(-1, 3)
    omega = np.array([edge[3] for edge in edges], dtype=float).reshape(-1, 3, 3)
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    offset = np.column_stack([cz * z[:, 0] + sz * z[:, 1], cz * z[:, 1] - sz * z[:, 0], z[:, 2]])
    J = np.zeros((m, 3, 7))
    J[:, 2, 2], J[:, 2, 5] = -1.0, 1.0  # the constant entries of A and B
    # Where each edge's 6 x 7 block [J'OJ | J'Oe] goes in the (3n) x (3n + 1) matrix [H | b]:
    # rows and columns 3i..3i+2 and 3j..3j+2, and b as the last column. One bincount then adds
    # up every block (H is small here: a dense solve is the fastest).
    cells = np.hstack([3 * i[:, None] + np.arange(3), 3 * j[:, None] + np.arange(3)])
    columns = np.hstack([cells, np.full((m, 1), 3 * n)])
    flat = (cells[:, :, None] * (3 * n + 1) + columns[:, None, :]).ravel()
    for _ in range(int(iterations)):
        linearise(x, i, j, offset, J)
        blocks = (J[:, :, :6].transpose(0, 2, 1) @ omega) @ J
        hb = np.bincount(flat, blocks.ravel(), 3 * n * (3 * n + 1)).reshape(3 * n, 3 * n + 1)
        x[1:] += np.linalg.solve(hb[3:, 3:-1], -hb[3:, -1]).reshape(-1, 3)  # pose 0 held fixed
        x[:, 2] = wrap(x[:, 2])
    # every pose seen from pose 0, x_0^-1 (+) x_k
    c, s = np.cos(x[0, 2]), np.sin(x[0, 2])
    d = x - x[0]
    return np.column_stack([c * d[:, 0] + s * d[:, 1], c * d[:, 1] - s * d[:, 0], wrap(d[:, 2])])
