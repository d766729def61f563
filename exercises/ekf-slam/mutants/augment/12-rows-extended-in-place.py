# mistake: appends the new columns and rows to P itself, so the caller's covariance grows (and a tuple or an array cannot)
import math


def augment(mu, P, z, R):
    n = len(P)
    r, a = z[0], mu[2] + z[1]
    c, s = math.cos(a), math.sin(a)
    Gr = [[1.0, 0.0, -r * s], [0.0, 1.0, r * c]]
    Gz = [[c, -r * s], [s, r * c]]
    cross = [[sum(Gr[i][k] * P[k][m] for k in range(3)) for m in range(n)] for i in range(2)]
    block = [
        [
            sum(cross[i][k] * Gr[j][k] for k in range(3))
            + sum(Gz[i][k] * R[k][m] * Gz[j][m] for k in range(2) for m in range(2))
            for j in range(2)
        ]
        for i in range(2)
    ]
    for m, row in enumerate(P):
        row.extend([cross[0][m], cross[1][m]])
    P.append(cross[0] + block[0])
    P.append(cross[1] + block[1])
    return P
