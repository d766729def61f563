# method: every factor at once with numpy, H assembled as a scipy.sparse matrix and spsolve
import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import spsolve


def _wrap(a):
    return np.arctan2(np.sin(a), np.cos(a))


def _read(text):
    odo, obs = [], []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "ODOMETRY":
            odo.append([float(v) for v in f[1:12]])
        elif f and f[0] == "LANDMARK":
            obs.append([float(v) for v in f[1:8]])
    return np.array(odo).reshape(-1, 11), np.array(obs).reshape(-1, 7)


def optimise_landmarks(text, iterations):
    odo, obs = _read(text)
    pose_ids = np.unique(np.concatenate([odo[:, 0], odo[:, 1], obs[:, 0]]).astype(np.int64))
    tree_ids = np.unique(obs[:, 1].astype(np.int64))
    oi = np.searchsorted(pose_ids, odo[:, 0].astype(np.int64))
    oj = np.searchsorted(pose_ids, odo[:, 1].astype(np.int64))
    li = np.searchsorted(pose_ids, obs[:, 0].astype(np.int64))
    ll = np.searchsorted(tree_ids, obs[:, 1].astype(np.int64))
    n, m = len(pose_ids), len(tree_ids)
    oz, lz = odo[:, 2:5], obs[:, 2:4]
    u = odo[:, 5:11]
    ocov = np.stack([u[:, [0, 1, 2]], u[:, [1, 3, 4]], u[:, [2, 4, 5]]], axis=1)
    v = obs[:, 4:7]
    lcov = np.stack([v[:, [0, 1]], v[:, [1, 2]]], axis=1)
    oinf, linf = np.linalg.inv(ocov), np.linalg.inv(lcov)

    x = np.zeros((n, 3))
    for k in range(len(odo)):  # the chain, in file order
        a, b, z = oi[k], oj[k], oz[k]
        c, s = np.cos(x[a, 2]), np.sin(x[a, 2])
        x[b] = [x[a, 0] + c * z[0] - s * z[1], x[a, 1] + s * z[0] + c * z[1], _wrap(x[a, 2] + z[2])]
    first = np.unique(ll, return_index=True)[1]
    p = x[li[first]]
    c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
    z = lz[first]
    trees = np.stack([p[:, 0] + c * z[:, 0] - s * z[:, 1], p[:, 1] + s * z[:, 0] + c * z[:, 1]], 1)

    size = 3 * n + 2 * m
    for _ in range(int(iterations)):
        # odometry
        xi, xj = x[oi], x[oj]
        ci, si = np.cos(xi[:, 2]), np.sin(xi[:, 2])
        cz, sz = np.cos(oz[:, 2]), np.sin(oz[:, 2])
        d = xj[:, :2] - xi[:, :2]
        lx, ly = ci * d[:, 0] + si * d[:, 1], -si * d[:, 0] + ci * d[:, 1]
        ux, uy = lx - oz[:, 0], ly - oz[:, 1]
        e = np.stack(
            [cz * ux + sz * uy, -sz * ux + cz * uy, _wrap(xj[:, 2] - xi[:, 2] - oz[:, 2])], 1
        )
        ct, st = np.cos(xi[:, 2] + oz[:, 2]), np.sin(xi[:, 2] + oz[:, 2])
        dlx, dly = -si * d[:, 0] + ci * d[:, 1], -ci * d[:, 0] - si * d[:, 1]
        jo = np.zeros((len(oi), 3, 6))
        jo[:, 0, 0], jo[:, 0, 1], jo[:, 1, 0], jo[:, 1, 1] = -ct, -st, st, -ct
        jo[:, 0, 2], jo[:, 1, 2], jo[:, 2, 2] = cz * dlx + sz * dly, -sz * dlx + cz * dly, -1.0
        jo[:, 0, 3], jo[:, 0, 4], jo[:, 1, 3], jo[:, 1, 4] = ct, st, -st, ct
        jo[:, 2, 5] = 1.0
        io = np.concatenate([3 * oi[:, None] + np.arange(3), 3 * oj[:, None] + np.arange(3)], 1)
        # sightings
        p = x[li]
        c, s = np.cos(p[:, 2]), np.sin(p[:, 2])
        dd = trees[ll] - p[:, :2]
        h = np.stack([c * dd[:, 0] + s * dd[:, 1], -s * dd[:, 0] + c * dd[:, 1]], 1)
        el = h - lz
        jl = np.zeros((len(li), 2, 5))
        jl[:, 0, 0], jl[:, 0, 1], jl[:, 1, 0], jl[:, 1, 1] = -c, -s, s, -c
        jl[:, 0, 2], jl[:, 1, 2] = h[:, 1], -h[:, 0]
        jl[:, 0, 3], jl[:, 0, 4], jl[:, 1, 3], jl[:, 1, 4] = c, s, -s, c
        il = np.concatenate(
            [3 * li[:, None] + np.arange(3), 3 * n + 2 * ll[:, None] + np.arange(2)], 1
        )
        rows, cols, vals = [], [], []
        g = np.zeros(size)
        for idx, jac, om, err in ((io, jo, oinf, e), (il, jl, linf, el)):
            jto = np.einsum("kai,kab->kib", jac, om)
            np.add.at(g, idx, np.einsum("kib,kb->ki", jto, err))
            w = idx.shape[1]
            rows.append(np.repeat(idx, w, 1).ravel())
            cols.append(np.tile(idx, (1, w)).ravel())
            vals.append(np.einsum("kib,kbj->kij", jto, jac).ravel())
        hm = coo_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size)
        ).tocsc()
        step = spsolve(hm[3:, 3:], -g[3:])
        x[1:] += step[: 3 * (n - 1)].reshape(-1, 3)
        x[:, 2] = _wrap(x[:, 2])
        trees = trees + step[3 * (n - 1) :].reshape(-1, 2)

    c0, s0 = np.cos(x[0, 2]), np.sin(x[0, 2])
    r0t = np.array([[c0, s0], [-s0, c0]])
    poses = np.column_stack([(x[:, :2] - x[0, :2]) @ r0t.T, _wrap(x[:, 2] - x[0, 2])])
    return np.concatenate([poses.ravel(), ((trees - x[0, :2]) @ r0t.T).ravel()])
