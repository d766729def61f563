import numpy as np
from scipy.linalg import solveh_banded

BANDED = 40  # from this many poses on, solve along the chain (measured: dense is faster below)


def _wrap(a):
    """Angles into (-pi, pi]."""
    return np.pi - np.remainder(np.pi - a, 2 * np.pi)


def _rot_t(theta):
    """``R(θ)ᵀ`` for every angle of ``theta``: shape (K, 2, 2)."""
    c, s = np.cos(theta), np.sin(theta)
    return np.stack([c, s, -s, c], axis=-1).reshape(-1, 2, 2)


def _read(text):
    """The ODOMETRY and LANDMARK lines as two float arrays, (M, 11) and (K, 7), file order."""
    odo, obs = [], []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "ODOMETRY":
            odo.append(f[1:12])
        elif f and f[0] == "LANDMARK":
            obs.append(f[1:8])
    return np.array(odo, dtype=float).reshape(-1, 11), np.array(obs, dtype=float).reshape(-1, 7)


def _solve(h, b, n):
    """Solve ``h @ step = b`` for the state without pose 0: ``3(n - 1)`` pose columns, then
    the trees'.

    Odometry only links neighbours, so the poses' block ``T`` of ``h`` is banded (five
    diagonals above the main one) and the trees' block ``D`` is small. For a long chain, solve
    ``T`` banded for the trees' columns ``C`` and the poses' right-hand side at once, then the
    trees from the Schur complement ``D - Cᵀ T⁻¹ C``, then the poses. A short one is cheaper
    dense.
    """
    if n < BANDED:
        return np.linalg.solve(h, b)
    p = 3 * (n - 1)
    t, c, d = h[:p, :p], h[:p, p:], h[p:, p:]
    band = np.zeros((6, p))  # upper band storage: band[5 - k, k:] is T's k-th superdiagonal
    for k in range(6):
        band[5 - k, k:] = np.diagonal(t, k)
    y = solveh_banded(band, np.column_stack([c, b[:p]]), check_finite=False)
    yc, yb = y[:, :-1], y[:, -1]
    trees = np.linalg.solve(d - c.T @ yc, b[p:] - c.T @ yb)
    return np.concatenate([yb - yc @ trees, trees])


def optimise_landmarks(text, iterations):
    odo, obs = _read(text)
    # the chain, in file order: ODOMETRY line k links pose k to pose k + 1
    pose_ids = np.concatenate([odo[:1, 0], odo[:, 1]])
    tree_ids, seen = np.unique(obs[:, 1], return_inverse=True)
    n, m = len(pose_ids), len(tree_ids)
    seen_from = np.searchsorted(pose_ids, obs[:, 0])
    oz, lz = odo[:, 2:5], obs[:, 2:4]
    # information matrices Σ⁻¹, from the upper triangles
    oinf = np.linalg.inv(odo[:, [5, 6, 7, 6, 8, 9, 7, 9, 10]].reshape(-1, 3, 3))
    linf = np.linalg.inv(obs[:, [4, 5, 5, 6]].reshape(-1, 2, 2))

    # initial guess: dead reckoning along the chain, then every tree at its first sighting
    # (a row vector times R(θ)ᵀ is (R(θ) z)ᵀ)
    x = np.zeros((n, 3))
    x[1:, 2] = np.cumsum(oz[:, 2])
    x[1:, :2] = np.cumsum((oz[:, None, :2] @ _rot_t(x[:-1, 2]))[:, 0], axis=0)  # R(θ_k) z_k
    x[:, 2] = _wrap(x[:, 2])
    first = np.unique(seen, return_index=True)[1]
    trees = x[seen_from[first], :2] + (lz[first, None] @ _rot_t(x[seen_from[first], 2]))[:, 0]

    # the state columns of every factor, and where each entry of its J^T Ω J lands in H
    size = 3 * n + 2 * m
    ocols = 3 * np.arange(n - 1)[:, None] + np.arange(6)  # poses k and k + 1, side by side
    lcols = np.concatenate(
        [3 * seen_from[:, None] + np.arange(3), 3 * n + 2 * seen[:, None] + np.arange(2)], 1
    )
    cols = np.concatenate([ocols.ravel(), lcols.ravel()])
    cells = np.concatenate([(c[:, :, None] * size + c[:, None, :]).ravel() for c in (ocols, lcols)])

    # [J | e] of every factor: the Jacobians' constant entries are set once
    jo = np.zeros((n - 1, 3, 7))
    jo[:, 2, 2], jo[:, 2, 5] = -1.0, 1.0
    jl = np.zeros((len(obs), 2, 6))
    rzz = (_rot_t(oz[:, 2]) @ oz[:, :2, None])[:, :, 0]  # R(dθ)ᵀ (dx, dy)
    for _ in range(int(iterations)):
        # odometry: e = (R(θ_k + dθ)ᵀ (t_k+1 - t_k) - R(dθ)ᵀ (dx, dy), θ_k+1 - θ_k - dθ);
        # with r = R(θ_k + dθ)ᵀ (t_k+1 - t_k): A = [[-Rᵀ, (r_y, -r_x)ᵀ], [0, -1]], B = diag(Rᵀ, 1)
        rt = _rot_t(x[:-1, 2] + oz[:, 2])
        r = (rt @ (x[1:, :2] - x[:-1, :2])[:, :, None])[:, :, 0]
        jo[:, :2, :2], jo[:, :2, 3:5] = -rt, rt
        jo[:, 0, 2], jo[:, 1, 2] = r[:, 1], -r[:, 0]
        jo[:, :2, 6] = r - rzz
        jo[:, 2, 6] = _wrap(x[1:, 2] - x[:-1, 2] - oz[:, 2])
        # sightings: e = r - z with r = R(θ_i)ᵀ (l - t_i): A = [-Rᵀ | (r_y, -r_x)ᵀ], B = Rᵀ
        rt = _rot_t(x[seen_from, 2])
        r = (rt @ (trees[seen] - x[seen_from, :2])[:, :, None])[:, :, 0]
        jl[:, :, :2], jl[:, :, 3:5] = -rt, rt
        jl[:, 0, 2], jl[:, 1, 2] = r[:, 1], -r[:, 0]
        jl[:, :, 5] = r - lz
        # J^T Ω [J | e] holds a factor's blocks of H and its entries of b; sum them all
        qo = jo[:, :, :6].transpose(0, 2, 1) @ oinf @ jo
        ql = jl[:, :, :5].transpose(0, 2, 1) @ linf @ jl
        h = np.bincount(
            cells, np.concatenate([qo[:, :, :6].ravel(), ql[:, :, :5].ravel()]), size * size
        )
        b = np.bincount(cols, np.concatenate([qo[:, :, 6].ravel(), ql[:, :, 5].ravel()]), size)
        step = _solve(h.reshape(size, size)[3:, 3:], -b[3:], n)  # pose 0 held fixed
        x[1:] += step[: 3 * (n - 1)].reshape(-1, 3)
        x[:, 2] = _wrap(x[:, 2])
        trees = trees + step[3 * (n - 1) :].reshape(-1, 2)

    # everything seen from pose 0 (which never moved from the origin, but say it anyway)
    r0t = _rot_t(x[:1, 2])[0]
    poses = np.column_stack([(x[:, :2] - x[0, :2]) @ r0t.T, _wrap(x[:, 2] - x[0, 2])])
    return np.concatenate([poses.ravel(), ((trees - x[0, :2]) @ r0t.T).ravel()])
