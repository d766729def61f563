# method: homogeneous matrices, one stacked Jacobian by central differences, whitened lstsq
import math

import numpy as np


def _mat(p):
    c, s = math.cos(p[2]), math.sin(p[2])
    return np.array([[c, -s, p[0]], [s, c, p[1]], [0.0, 0.0, 1.0]])


def _inv(m):
    out = np.eye(3)
    out[:2, :2] = m[:2, :2].T
    out[:2, 2] = -m[:2, :2].T @ m[:2, 2]
    return out


def _odo(v, z):
    m = _inv(_mat(z)) @ _inv(_mat(v[:3])) @ _mat(v[3:])
    return np.array([m[0, 2], m[1, 2], math.atan2(m[1, 0], m[0, 0])])


def _obs(v, z):
    return (_inv(_mat(v[:3])) @ np.array([v[3], v[4], 1.0]))[:2] - z


def optimise_landmarks(text, iterations):
    odo, obs = [], []
    for line in text.splitlines():
        f = line.split()
        if f and f[0] == "ODOMETRY":
            c = [float(v) for v in f[6:12]]
            cov = np.array([[c[0], c[1], c[2]], [c[1], c[3], c[4]], [c[2], c[4], c[5]]])
            odo.append((int(f[1]), int(f[2]), [float(v) for v in f[3:6]], cov))
        elif f and f[0] == "LANDMARK":
            cov = np.array([[float(f[5]), float(f[6])], [float(f[6]), float(f[7])]])
            obs.append((int(f[1]), int(f[2]), np.array([float(f[3]), float(f[4])]), cov))
    poses = sorted({o[0] for o in odo} | {o[1] for o in odo} | {o[0] for o in obs})
    pk = {p: k for k, p in enumerate(poses)}
    lk = {p: k for k, p in enumerate(sorted({o[1] for o in obs}))}
    n, m = len(pk), len(lk)
    state = np.zeros(3 * n + 2 * m)
    for i, j, z, _ in odo:
        a, b = 3 * pk[i], 3 * pk[j]
        mj = _mat(state[a : a + 3]) @ _mat(z)
        state[b : b + 3] = [mj[0, 2], mj[1, 2], math.atan2(mj[1, 0], mj[0, 0])]
    seen = set()
    for i, tree, z, _ in obs:
        if tree not in seen:
            seen.add(tree)
            point = _mat(state[3 * pk[i] : 3 * pk[i] + 3]) @ np.array([z[0], z[1], 1.0])
            state[3 * n + 2 * lk[tree] : 3 * n + 2 * lk[tree] + 2] = point[:2]
    # whitening: e' = W e with Wᵀ W = Ω, so e'ᵀ e' = eᵀ Ω e
    factors = []
    for i, j, z, cov in odo:
        cols = [*range(3 * pk[i], 3 * pk[i] + 3), *range(3 * pk[j], 3 * pk[j] + 3)]
        factors.append((_odo, cols, z, np.linalg.cholesky(np.linalg.inv(cov)).T, 2))
    for i, tree, z, cov in obs:
        cols = [*range(3 * pk[i], 3 * pk[i] + 3), 3 * n + 2 * lk[tree], 3 * n + 2 * lk[tree] + 1]
        factors.append((_obs, cols, z, np.linalg.cholesky(np.linalg.inv(cov)).T, None))
    rows = sum(len(f[2]) if f[0] is _odo else 2 for f in factors)
    for _ in range(int(iterations)):
        jac = np.zeros((rows, len(state)))
        res = np.zeros(rows)
        r = 0
        for error, cols, z, w, angle in factors:
            v = state[cols]
            e = error(v, z)
            k = len(e)
            res[r : r + k] = w @ e
            for c_, col in enumerate(cols):
                hi, lo = v.copy(), v.copy()
                hi[c_] += 1e-6
                lo[c_] -= 1e-6
                d = error(hi, z) - error(lo, z)
                if angle is not None:
                    d[angle] = math.atan2(math.sin(d[angle]), math.cos(d[angle]))
                jac[r : r + k, col] = w @ d / 2e-6
            r += k
        free = jac[:, 3:]
        state[3:] += np.linalg.solve(free.T @ free, -free.T @ res)
        heads = state[2 : 3 * n : 3]
        state[2 : 3 * n : 3] = np.arctan2(np.sin(heads), np.cos(heads))
    return state
