# method: whiten R with its Cholesky factor, then two scalar updates in plain Python loops
import math


def update_covariance(P, H, R):
    n = len(P)
    P = [[float(v) for v in row] for row in P]
    # R = L Lᵀ; the measurement L⁻¹ z has noise I, so range and bearing become independent
    l00 = math.sqrt(R[0][0])
    l10 = R[1][0] / l00
    l11 = math.sqrt(R[1][1] - l10 * l10)
    h0 = [v / l00 for v in H[0]]
    h1 = [(H[1][k] - l10 * h0[k]) / l11 for k in range(n)]
    for h in (h0, h1):
        ph = [sum(P[i][k] * h[k] for k in range(n)) for i in range(n)]
        s = sum(h[i] * ph[i] for i in range(n)) + 1.0
        P = [[P[i][k] - ph[i] * ph[k] / s for k in range(n)] for i in range(n)]
    return P
