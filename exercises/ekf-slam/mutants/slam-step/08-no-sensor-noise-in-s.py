# mistake: S = H P Hᵀ: the update forgets the measurement noise
import math

import numpy as np


def wrap(a):
    a = math.fmod(a + math.pi, 2 * math.pi)
    if a <= 0:
        a += 2 * math.pi
    return a - math.pi


def ekf_slam_step(mu, Sigma, u, M, z, ids, R):
    mu = np.array(mu, dtype=float)
    P = np.array(Sigma, dtype=float)
    M = np.array(M, dtype=float)
    R = np.array(R, dtype=float)
    rot1, trans, rot2 = (float(v) for v in u)

    # prediction: only the pose moves
    x, y, th = mu[:3]
    a = th + rot1
    G = np.array([[1, 0, -trans * math.sin(a)], [0, 1, trans * math.cos(a)], [0, 0, 1]])
    V = np.array(
        [[-trans * math.sin(a), math.cos(a), 0], [trans * math.cos(a), math.sin(a), 0], [1, 0, 1]]
    )
    mu[:3] = [x + trans * math.cos(a), y + trans * math.sin(a), wrap(th + rot1 + rot2)]
    P[:3, :] = G @ P[:3, :]
    P[:, :3] = P[:, :3] @ G.T
    P[:3, :3] += V @ M @ V.T

    for (r, phi), j in zip(z, ids):
        r, phi, j = float(r), float(phi), int(j)
        n = len(mu)
        k = 3 + 2 * j
        if k < n:  # a mapped landmark: update
            dx, dy = mu[k] - mu[0], mu[k + 1] - mu[1]
            q = dx * dx + dy * dy
            s = math.sqrt(q)
            H = np.zeros((2, n))
            H[:, :3] = [[-dx / s, -dy / s, 0], [dy / q, -dx / q, -1]]
            H[:, k : k + 2] = [[dx / s, dy / s], [-dy / q, dx / q]]
            nu = np.array([r - s, wrap(phi - (math.atan2(dy, dx) - mu[2]))])
            S = H @ P @ H.T + 1e-9 * np.eye(2)
            K = np.linalg.solve(S, H @ P).T
            mu = mu + K @ nu
            mu[2] = wrap(mu[2])
            A = np.eye(n) - K @ H
            P = A @ P @ A.T + K @ R @ K.T
        else:  # a new landmark: augment
            b = mu[2] + phi
            c, sn = math.cos(b), math.sin(b)
            Gr = np.array([[1, 0, -r * sn], [0, 1, r * c]])
            Gz = np.array([[c, -r * sn], [sn, r * c]])
            new = np.zeros((n + 2, n + 2))
            new[:n, :n] = P
            new[n:, :n] = Gr @ P[:3, :]
            new[:n, n:] = new[n:, :n].T
            new[n:, n:] = Gr @ P[:3, :3] @ Gr.T + Gz @ R @ Gz.T
            P = new
            mu = np.concatenate([mu, [mu[0] + r * c, mu[1] + r * sn]])
    return np.vstack([mu, P])
