import numpy as np
from scipy.sparse import csc_matrix
from scipy.sparse.linalg import spsolve

DENSE_UP_TO = 40
"""Poses up to which H is a dense matrix solved by np.linalg.solve; a larger graph's H is a
csc matrix solved by spsolve (measured: the dense solve is the faster up to 40-80 poses,
and multithreaded BLAS on a busy machine makes it much slower beyond that)."""


def wrap(a):
    """Angles into (-pi, pi]: pi minus (pi - a) reduced into [0, 2 pi)."""
    return np.pi - np.remainder(np.pi - a, 2 * np.pi)


def robust_weights(kind, s, k):
    k2 = k * k
    if kind == "huber":
        return np.where(s <= k2, 1.0, k / np.sqrt(np.maximum(s, k2)))
    if kind == "cauchy":
        return 1.0 / (1.0 + s / k2)
    if kind == "dcs":
        return np.minimum(1.0, 2.0 * k2 / (k2 + s)) ** 2
    return np.ones_like(s)  # "l2"


def read_g2o(text):
    """The poses (n x 3, in id order), every edge's ends i and j, its measurement z (m x 3) and
    its information matrix (m x 3 x 3)."""
    ids, poses, ends, numbers = [], [], [], []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "VERTEX_SE2":
            ids.append(int(f[1]))
            poses.append([float(v) for v in f[2:5]])
        elif f and f[0] == "EDGE_SE2":
            ends.append((int(f[1]), int(f[2])))
            numbers.append([float(v) for v in f[3:12]])
    x = np.empty((len(ids), 3))
    x[ids] = poses
    i, j = np.array(ends, dtype=int).reshape(-1, 2).T
    numbers = np.array(numbers, dtype=float).reshape(-1, 9)
    # I11 I12 I13 I22 I23 I33 into the symmetric 3 x 3 matrix
    om = numbers[:, [3, 4, 5, 4, 6, 7, 5, 7, 8]].reshape(-1, 3, 3)
    return x, i, j, numbers[:, :3], om


def assembler(i, j, n):
    """A function summing the edges' 7 x 7 blocks [A B e]^T Omega [A B e] (m x 7 x 7) into
    H and b without pose 0's rows and columns: H dense for a small graph, else csc."""
    m, size = len(i), 3 * n - 3
    # the 7 places of an edge's block: x_i's unknowns, x_j's (pose 0's are negative), then b
    place = np.full((m, 7), size)
    place[:, :3] = 3 * i[:, None] - 3 + np.arange(3)
    place[:, 3:6] = 3 * j[:, None] - 3 + np.arange(3)
    rows, cols = np.repeat(place, 7, axis=1).ravel(), np.tile(place, 7).ravel()
    in_h = (rows >= 0) & (cols >= 0) & (rows < size) & (cols < size)
    in_b = (rows >= 0) & (rows < size) & (cols == size)
    b_rows = rows[in_b]
    if n <= DENSE_UP_TO:
        cells = rows[in_h] * size + cols[in_h]

        def assemble(blocks):
            values = blocks.ravel()
            h = np.bincount(cells, values[in_h], size * size).reshape(size, size)
            return h, np.bincount(b_rows, values[in_b], size)

        return assemble
    # the csc pattern of H once: its stored cells (column-major numbers) and, for every
    # entry, which of them it adds to
    stored, cell_of = np.unique(cols[in_h] * size + rows[in_h], return_inverse=True)
    indices, indptr = stored % size, np.searchsorted(stored, np.arange(size + 1) * size)

    def assemble(blocks):
        values = blocks.ravel()
        data = np.bincount(cell_of, values[in_h], len(stored))
        h = csc_matrix((data, indices, indptr), shape=(size, size))
        return h, np.bincount(b_rows, values[in_b], size)

    return assemble


def robust_optimise(text, kernel, k, iterations):
    x, i, j, z, om = read_g2o(text)
    n, m = len(x), len(i)
    loop = np.abs(i - j) != 1
    # e = R(theta_i + dtheta)^T (t_j - t_i) - R(dtheta)^T t_z; the last term never changes
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    tz = np.stack([cz * z[:, 0] + sz * z[:, 1], cz * z[:, 1] - sz * z[:, 0]], axis=1)
    assemble = assembler(i, j, n)
    # each edge's 3 x 7 matrix [A B e]: the Jacobians for x_i and x_j, then the error, so that
    # [A B e]^T Omega [A B e] holds its blocks of H, of b (last column) and s (last entry)
    jac = np.zeros((m, 3, 7))
    jac[:, 2, 2], jac[:, 2, 5] = -1.0, 1.0
    for _ in range(iterations):
        xi = x[i]
        d = x[j] - xi
        a = xi[:, 2] + z[:, 2]
        c, s = np.cos(a), np.sin(a)
        px, py = c * d[:, 0] + s * d[:, 1], c * d[:, 1] - s * d[:, 0]  # R(a)^T (t_j - t_i)
        jac[:, 0, 3], jac[:, 0, 4], jac[:, 1, 3], jac[:, 1, 4] = c, s, -s, c
        jac[:, :2, :2] = -jac[:, :2, 3:5]
        jac[:, 0, 2], jac[:, 1, 2] = py, -px
        jac[:, 0, 6], jac[:, 1, 6] = px - tz[:, 0], py - tz[:, 1]
        jac[:, 2, 6] = wrap(d[:, 2] - z[:, 2])
        blocks = jac.transpose(0, 2, 1) @ (om @ jac)
        # weight w(s) for the loop closures, 1 for odometry: scales the edge's whole block
        w = np.where(loop, robust_weights(kernel, blocks[:, 6, 6], k), 1.0)
        h, b = assemble(blocks * w[:, None, None])
        delta = np.linalg.solve(h, -b) if n <= DENSE_UP_TO else spsolve(h, -b)
        x[1:] += delta.reshape(-1, 3)  # pose 0 held fixed
        x[:, 2] = wrap(x[:, 2])
    # every pose seen from pose 0
    c0, s0 = np.cos(x[0, 2]), np.sin(x[0, 2])
    d = x - x[0]
    return np.stack(
        [c0 * d[:, 0] + s0 * d[:, 1], c0 * d[:, 1] - s0 * d[:, 0], wrap(d[:, 2])], axis=1
    )
