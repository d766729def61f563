# method: every Jacobian by central finite differences of the models themselves
import math

import numpy as np


def _wrap(a):
    return (
        math.remainder(a, 2 * math.pi)
        if abs(math.remainder(a, 2 * math.pi)) != math.pi
        else math.pi
    )


def _jac(f, x, h=1e-6):
    x = np.asarray(x, dtype=float)
    cols = []
    for i in range(x.size):
        e = np.zeros(x.size)
        e[i] = h
        d = np.asarray(f(x + e)) - np.asarray(f(x - e))
        cols.append(d / (2 * h))
    return np.column_stack(cols)


def _move(x, u):
    return np.array(
        [
            x[0] + u[1] * math.cos(x[2] + u[0]),
            x[1] + u[1] * math.sin(x[2] + u[0]),
            x[2] + u[0] + u[2],
        ]
    )


def ekf_slam_step(mu, Sigma, u, M, z, ids, R):
    mu = np.array(mu, dtype=float)
    P = np.array(Sigma, dtype=float)
    u = np.array(u, dtype=float)
    M, R = np.array(M, dtype=float), np.array(R, dtype=float)
    pose = mu[:3].copy()
    G = _jac(lambda p: _move(p, u), pose)
    V = _jac(lambda c: _move(pose, c), u)
    mu[:3] = _move(pose, u)
    mu[2] = _wrap(mu[2])
    P[:3] = G @ P[:3]
    P[:, :3] = P[:, :3] @ G.T
    P[:3, :3] += V @ M @ V.T
    for zk, j in zip(np.array(z, dtype=float), ids):
        j, n = int(j), mu.size
        if 3 + 2 * j < n:

            def h(state, j=j):
                dx, dy = state[3 + 2 * j] - state[0], state[4 + 2 * j] - state[1]
                # the bearing relative to the current estimate, so differences never jump by 2π
                return np.array(
                    [math.hypot(dx, dy), _wrap(math.atan2(dy, dx) - state[2] - (zk[1]))]
                )

            H = _jac(h, mu)
            nu = -h(mu)
            nu[0] += zk[0]
            S = H @ P @ H.T + R
            K = P @ H.T @ np.linalg.inv(S)
            mu = mu + K @ nu
            mu[2] = _wrap(mu[2])
            A = np.eye(n) - K @ H
            P = A @ P @ A.T + K @ R @ K.T
        else:

            def g(x):  # x = (pose, r, phi)
                return np.array(
                    [x[0] + x[3] * math.cos(x[2] + x[4]), x[1] + x[3] * math.sin(x[2] + x[4])]
                )

            x0 = np.concatenate([mu[:3], zk])
            J = _jac(g, x0)
            Gr, Gz = J[:, :3], J[:, 3:]
            cross = Gr @ P[:3]
            P = np.block([[P, cross.T], [cross, Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T]])
            mu = np.concatenate([mu, g(x0)])
    return np.vstack([mu, P])
