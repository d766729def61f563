import numpy as np
from scipy.sparse import csc_matrix, diags
from scipy.sparse.linalg import spsolve

DENSE_UP_TO = 40
"""Poses up to which H is a dense matrix solved by np.linalg.solve; a larger graph's H is a
csc matrix solved by spsolve (measured: the dense solve is the faster up to 40-80 poses,
and multithreaded BLAS on a busy machine makes it much slower beyond that)."""


def wrap(a):
    """Angles into (-pi, pi]: pi minus (pi - a) reduced into [0, 2 pi)."""
    return np.pi - np.remainder(np.pi - a, 2 * np.pi)


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


def levenberg_marquardt(poses, edges, lam0, trials):
    x = np.array(poses, dtype=float)  # a copy: the input is left alone
    n, m = len(x), len(edges)
    i = np.array([int(e[0]) for e in edges], dtype=int)
    j = np.array([int(e[1]) for e in edges], dtype=int)
    z = np.array([e[2] for e in edges], dtype=float).reshape(m, 3)
    om = np.array([e[3] for e in edges], dtype=float).reshape(m, 3, 3)
    # e = R(theta_i + dtheta)^T (t_j - t_i) - R(dtheta)^T t_z; the last term never changes
    cz, sz = np.cos(z[:, 2]), np.sin(z[:, 2])
    tz = np.stack([cz * z[:, 0] + sz * z[:, 1], cz * z[:, 1] - sz * z[:, 0]], axis=1)
    assemble = assembler(i, j, n)
    # each edge's 3 x 7 matrix [A B e]: the Jacobians for x_i and x_j, then the error, so that
    # [A B e]^T Omega [A B e] holds its blocks of H and of b (last column)
    jac = np.zeros((m, 3, 7))
    jac[:, 2, 2], jac[:, 2, 5] = -1.0, 1.0

    def errors(x):
        """Every edge's error (m x 3), and the cosine and sine of theta_i + dtheta."""
        xi = x[i]
        d = x[j] - xi
        a = xi[:, 2] + z[:, 2]
        c, s = np.cos(a), np.sin(a)
        e = np.stack(
            [
                c * d[:, 0] + s * d[:, 1] - tz[:, 0],
                c * d[:, 1] - s * d[:, 0] - tz[:, 1],
                wrap(d[:, 2] - z[:, 2]),
            ],
            axis=1,
        )
        return e, c, s

    def chi2(e):
        return float(np.einsum("ka,kab,kb->", e, om, e))

    def system(e, c, s):
        """H and b (pose 0 left out) from what errors() returned at some poses."""
        jac[:, 0, 3], jac[:, 0, 4], jac[:, 1, 3], jac[:, 1, 4] = c, s, -s, c
        jac[:, :2, :2] = -jac[:, :2, 3:5]
        # d/dtheta_i of R(a)^T (t_j - t_i) = (p_y, -p_x) with p = R(a)^T (t_j - t_i) = e + t_z
        jac[:, 0, 2], jac[:, 1, 2] = e[:, 1] + tz[:, 1], -e[:, 0] - tz[:, 0]
        jac[:, :, 6] = e
        return assemble(jac.transpose(0, 2, 1) @ (om @ jac))

    lam, nu = float(lam0), 2.0
    e, c, s = errors(x)
    current = chi2(e)
    h = None
    for _ in range(int(trials)):
        if h is None:  # H and b change only when the poses do
            h, b = system(e, c, s)
        damping = lam * h.diagonal()  # Marquardt: lam diag(H)
        if n <= DENSE_UP_TO:
            delta = np.linalg.solve(h + np.diag(damping), -b)
        else:
            delta = spsolve(h + diags(damping, format="csc"), -b)
        candidate = x.copy()
        candidate[1:] += delta.reshape(-1, 3)  # pose 0 unchanged
        moved = errors(candidate)
        new = chi2(moved[0])
        predicted = -2.0 * (b @ delta) - delta @ (h @ delta)
        rho = (current - new) / predicted if predicted > 0 else -1.0
        if rho > 0:  # accept
            x, current, h = candidate, new, None
            e, c, s = moved  # the errors at the new poses, for their H and b
            lam *= max(1.0 / 3.0, 1.0 - (2.0 * rho - 1.0) ** 3)
            nu = 2.0
        else:  # reject: keep x, damp harder
            lam *= nu
            nu *= 2.0
    # every pose seen from pose 0
    c0, s0 = np.cos(x[0, 2]), np.sin(x[0, 2])
    d = x - x[0]
    return np.stack(
        [c0 * d[:, 0] + s0 * d[:, 1], c0 * d[:, 1] - s0 * d[:, 0], wrap(d[:, 2])], axis=1
    )
