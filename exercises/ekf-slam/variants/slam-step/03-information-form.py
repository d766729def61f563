# method: the update in information form, P⁺ = (P⁻¹ + Hᵀ R⁻¹ H)⁻¹, μ⁺ = μ + P⁺ Hᵀ R⁻¹ ν
import math

import numpy as np


def ekf_slam_step(mu, Sigma, u, M, z, ids, R):
    mu = [float(v) for v in mu]
    P = np.array(Sigma, dtype=float)
    M = np.array(M, dtype=float)
    Rm = np.array(R, dtype=float)
    Ri = np.linalg.inv(Rm)
    t1, d, t2 = (float(v) for v in u)
    x, y, th = mu[:3]
    c, s = math.cos(th + t1), math.sin(th + t1)
    G = np.eye(len(mu))
    G[0, 2], G[1, 2] = -d * s, d * c
    V = np.zeros((len(mu), 3))
    V[:3] = [[-d * s, c, 0], [d * c, s, 0], [1, 0, 1]]
    heading = (th + t1 + t2 + math.pi) % (2 * math.pi) - math.pi
    if heading == -math.pi:
        heading = math.pi
    mu[:3] = [x + d * c, y + d * s, heading]
    P = G @ P @ G.T + V @ M @ V.T
    mu = np.array(mu)
    for k in range(len(ids)):
        j = int(ids[k])
        r, phi = float(z[k][0]), float(z[k][1])
        n = len(mu)
        if 3 + 2 * j < n:
            lm = mu[3 + 2 * j : 5 + 2 * j]
            delta = lm - mu[:2]
            q = float(delta @ delta)
            rr = math.sqrt(q)
            H = np.zeros((2, n))
            H[0, :2], H[1, :2], H[1, 2] = -delta / rr, [delta[1] / q, -delta[0] / q], -1
            H[0, 3 + 2 * j : 5 + 2 * j] = delta / rr
            H[1, 3 + 2 * j : 5 + 2 * j] = [-delta[1] / q, delta[0] / q]
            e = phi - math.atan2(delta[1], delta[0]) + mu[2]
            e = math.atan2(math.sin(e), math.cos(e))
            nu = np.array([r - rr, e])
            Pn = np.linalg.inv(np.linalg.inv(P) + H.T @ Ri @ H)
            mu = mu + Pn @ H.T @ Ri @ nu
            mu[2] = math.atan2(math.sin(mu[2]), math.cos(mu[2]))
            P = (Pn + Pn.T) / 2
        else:
            a = mu[2] + phi
            Gr = np.array([[1, 0, -r * math.sin(a)], [0, 1, r * math.cos(a)]])
            Gz = np.array([[math.cos(a), -r * math.sin(a)], [math.sin(a), r * math.cos(a)]])
            top = np.hstack([P, (Gr @ P[:3]).T])
            bottom = np.hstack([Gr @ P[:3], Gr @ P[:3, :3] @ Gr.T + Gz @ Rm @ Gz.T])
            P = np.vstack([top, bottom])
            mu = np.append(mu, [mu[0] + r * math.cos(a), mu[1] + r * math.sin(a)])
    return np.vstack([mu, P])
