# method: plain Python: explicit 3x3 products, the 3x3 inverses by cofactors
import math


def inv3(m):
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    return [
        [(e * i - f * h) / det, (c * h - b * i) / det, (b * f - c * e) / det],
        [(f * g - d * i) / det, (a * i - c * g) / det, (c * d - a * f) / det],
        [(d * h - e * g) / det, (b * g - a * h) / det, (a * e - b * d) / det],
    ]


def mul(a, b):
    return [
        [sum(a[r][k] * b[k][c] for k in range(len(b))) for c in range(len(b[0]))]
        for r in range(len(a))
    ]


def tr(a):
    return [list(row) for row in zip(*a)]


def closure_nis(xi, xj, P, z, info):
    ti, tz = xi[2], z[2]
    ci, si, cz, sz = math.cos(ti), math.sin(ti), math.cos(tz), math.sin(tz)
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    ux, uy = ci * dx + si * dy - z[0], -si * dx + ci * dy - z[1]
    e = [cz * ux + sz * uy, -sz * ux + cz * uy, math.remainder(xj[2] - ti - tz, 2 * math.pi)]
    c, s = math.cos(ti + tz), math.sin(ti + tz)  # R_z^T R_i^T = R(ti + tz)^T
    lx, ly = -si * dx + ci * dy, -ci * dx - si * dy
    A = [[-c, -s, cz * lx + sz * ly], [s, -c, -sz * lx + cz * ly], [0.0, 0.0, -1.0]]
    B = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]]
    Q = [[float(v) for v in row] for row in P]
    Sii = [row[:3] for row in Q[:3]]
    Sij = [row[3:] for row in Q[:3]]
    Sjj = [row[3:] for row in Q[3:]]
    S = mul(mul(A, Sii), tr(A))
    for term in (
        mul(mul(A, Sij), tr(B)),
        mul(mul(B, tr(Sij)), tr(A)),
        mul(mul(B, Sjj), tr(B)),
        inv3([[float(v) for v in row] for row in info]),
    ):
        S = [[S[r][q] + term[r][q] for q in range(3)] for r in range(3)]
    w = mul(inv3(S), [[v] for v in e])
    return sum(e[r] * w[r][0] for r in range(3))
