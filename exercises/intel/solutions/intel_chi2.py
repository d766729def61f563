import numpy as np
from scipy.sparse import csc_matrix
from scipy.sparse.linalg import spsolve

# H is sparse (a 3x3 block per pose and per edge's pair of poses): on the whole INTEL graph
# (3681 unknowns) it is assembled as a scipy.sparse matrix and solved with spsolve (SuperLU, which
# orders the columns to keep the fill small). Up to this many poses a dense solve beats
# scipy.sparse's fixed overhead (measured: the two break even at about 65 poses).
DENSE_MAX_POSES = 64


def wrap(a):
    """Angles (an array) wrapped into (-pi, pi]."""
    return np.pi - np.remainder(np.pi - a, 2 * np.pi)


def read_g2o(text):
    """Poses (n x 3) and the edges as arrays: i, j (m), z (m x 3), information (m x 3 x 3)."""
    vertices, edges = [], []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "VERTEX_SE2":
            vertices.append(f[1:5])
        elif f and f[0] == "EDGE_SE2":
            edges.append(f[1:12])
    v = np.array(vertices, dtype=float).reshape(-1, 4)
    x = np.empty((len(v), 3))
    x[v[:, 0].astype(int)] = v[:, 1:]  # the ids run from 0 to n-1, in any order
    r = np.array(edges, dtype=float).reshape(-1, 11)
    # g2o writes the upper triangle I11 I12 I13 I22 I23 I33: pick the full matrix row by row
    omega = r[:, [5, 6, 7, 6, 8, 9, 7, 9, 10]].reshape(-1, 3, 3)
    return x, r[:, 0].astype(int), r[:, 1].astype(int), r[:, 2:5], omega


def linearise(x, i, j, offset, J):
    """Fill J (m x 3 x 7), each edge's [A | B | e], at the poses x.

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


def step_solver(i, j, n):
    """A function that adds the edges' blocks [J'OJ | J'Oe] (m x 6 x 7) into H and b and returns
    the step of poses 1..n-1 (pose 0 is held fixed). H's pattern is the same at every step, so
    all the index arithmetic is done once, here."""
    m, n3 = len(i), 3 * n
    cells = np.hstack([3 * i[:, None] + np.arange(3), 3 * j[:, None] + np.arange(3)])  # m x 6
    if n <= DENSE_MAX_POSES:
        # one bincount adds every block into the (3n) x (3n + 1) matrix [H | b]
        columns = np.hstack([cells, np.full((m, 1), n3)])
        flat = (cells[:, :, None] * (n3 + 1) + columns[:, None, :]).ravel()

        def solve(blocks):
            hb = np.bincount(flat, blocks.ravel(), n3 * (n3 + 1)).reshape(n3, n3 + 1)
            return np.linalg.solve(hb[3:, 3:-1], -hb[3:, -1])

        return solve

    # sparse: the unknowns are poses 1..n-1; entries of pose 0 are dropped
    size = n3 - 3
    rows = np.broadcast_to(cells[:, :, None] - 3, (m, 6, 6))
    cols = np.broadcast_to(cells[:, None, :] - 3, (m, 6, 6))
    keep = (rows >= 0) & (cols >= 0)
    # the distinct cells of H in CSC order (column by column), and where each entry goes
    pattern, slot = np.unique(cols[keep] * size + rows[keep], return_inverse=True)
    indices = pattern % size
    indptr = np.searchsorted(pattern // size, np.arange(size + 1))

    def solve(blocks):
        b = np.bincount(cells.ravel(), blocks[:, :, 6].ravel(), n3)[3:]
        data = np.bincount(slot, blocks[:, :, :6][keep], len(pattern))
        return spsolve(csc_matrix((data, indices, indptr), shape=(size, size)), -b)

    return solve


def intel_chi2(text, iterations):
    x, i, j, z, omega = read_g2o(text)
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    offset = np.column_stack([cz * z[:, 0] + sz * z[:, 1], cz * z[:, 1] - sz * z[:, 0], z[:, 2]])
    J = np.zeros((len(i), 3, 7))
    J[:, 2, 2], J[:, 2, 5] = -1.0, 1.0  # the constant entries of A and B
    solve = step_solver(i, j, len(x))
    for _ in range(int(iterations)):
        linearise(x, i, j, offset, J)
        blocks = (J[:, :, :6].transpose(0, 2, 1) @ omega) @ J  # [J'OJ | J'Oe] of every edge
        x[1:] += solve(blocks).reshape(-1, 3)
    # the chi-square at the poses the last step produced (the headings need no wrapping: the
    # errors are wrapped and the Jacobians only use their cosines and sines)
    linearise(x, i, j, offset, J)
    e = J[:, :, 6]
    return float(np.einsum("ka,kab,kb->", e, omega, e))
