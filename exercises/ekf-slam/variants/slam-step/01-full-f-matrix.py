# method: the textbook matrices: F = blockdiag(G, I), F_x V M Vᵀ F_xᵀ, inverse S, (I − K H) P
import math

import numpy as np


def ekf_slam_step(mu, Sigma, u, M, z, ids, R):
    mu = np.asarray(mu, dtype=float).copy()
    P = np.asarray(Sigma, dtype=float).copy()
    M, R = np.asarray(M, dtype=float), np.asarray(R, dtype=float)
    d1, d, d2 = map(float, u)
    n = mu.size
    a = mu[2] + d1
    F = np.eye(n)
    F[0, 2], F[1, 2] = -d * math.sin(a), d * math.cos(a)
    Fx = np.zeros((n, 3))
    Fx[:3, :3] = np.eye(3)
    V = np.array(
        [[-d * math.sin(a), math.cos(a), 0.0], [d * math.cos(a), math.sin(a), 0.0], [1.0, 0.0, 1.0]]
    )
    mu[0] += d * math.cos(a)
    mu[1] += d * math.sin(a)
    mu[2] = math.atan2(math.sin(mu[2] + d1 + d2), math.cos(mu[2] + d1 + d2))
    P = F @ P @ F.T + Fx @ V @ M @ V.T @ Fx.T
    for zk, j in zip(np.asarray(z, dtype=float), list(ids)):
        j = int(j)
        n = mu.size
        if 3 + 2 * j < n:
            lx, ly = mu[3 + 2 * j], mu[4 + 2 * j]
            dx, dy = lx - mu[0], ly - mu[1]
            q = dx**2 + dy**2
            low = (
                np.array(
                    [
                        [
                            -math.sqrt(q) * dx,
                            -math.sqrt(q) * dy,
                            0,
                            math.sqrt(q) * dx,
                            math.sqrt(q) * dy,
                        ],
                        [dy, -dx, -q, -dy, dx],
                    ]
                )
                / q
            )
            Fj = np.zeros((5, n))
            Fj[:3, :3] = np.eye(3)
            Fj[3, 3 + 2 * j] = Fj[4, 4 + 2 * j] = 1
            H = low @ Fj
            zhat = np.array([math.sqrt(q), math.atan2(dy, dx) - mu[2]])
            nu = zk - zhat
            nu[1] = math.atan2(math.sin(nu[1]), math.cos(nu[1]))
            K = P @ H.T @ np.linalg.inv(H @ P @ H.T + R)
            mu = mu + K @ nu
            mu[2] = math.atan2(math.sin(mu[2]), math.cos(mu[2]))
            P = (np.eye(n) - K @ H) @ P
            P = (P + P.T) / 2
        else:
            r, phi = zk
            b = mu[2] + phi
            J = np.zeros((n + 2, n + 2))
            J[:n, :n] = np.eye(n)
            J[n:, :3] = [[1, 0, -r * math.sin(b)], [0, 1, r * math.cos(b)]]
            J[n:, n:] = [[math.cos(b), -r * math.sin(b)], [math.sin(b), r * math.cos(b)]]
            big = np.zeros((n + 2, n + 2))
            big[:n, :n], big[n:, n:] = P, R
            P = J @ big @ J.T
            mu = np.append(mu, [mu[0] + r * math.cos(b), mu[1] + r * math.sin(b)])
    return np.vstack([mu, P])
