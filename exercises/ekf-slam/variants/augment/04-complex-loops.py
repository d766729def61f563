# method: the landmark as the complex number p + r·e^{i(θ+φ)}; complex derivatives, plain loops
import cmath


def augment(mu, P, z, R):
    n = len(P)
    r, a = z[0], mu[2] + z[1]
    e = cmath.exp(1j * a)
    # ∂g/∂(x, y, θ) and ∂g/∂(r, φ), each column a complex number (dx + i·dy)
    gr = [1, 1j, 1j * r * e]
    gz = [e, 1j * r * e]
    rows = [[(v.real, v.imag) for v in gr], [(v.real, v.imag) for v in gz]]
    out = [[float(P[i][k]) if i < n and k < n else 0.0 for k in range(n + 2)] for i in range(n + 2)]
    for d in range(2):  # x_j (d = 0) and y_j (d = 1)
        for k in range(n):
            v = sum(rows[0][m][d] * P[m][k] for m in range(3))
            out[n + d][k] = v
            out[k][n + d] = v
        for d2 in range(2):
            pose_part = sum(
                rows[0][m][d] * P[m][q] * rows[0][q][d2] for m in range(3) for q in range(3)
            )
            noise_part = sum(
                rows[1][m][d] * R[m][q] * rows[1][q][d2] for m in range(2) for q in range(2)
            )
            out[n + d][n + d2] = pose_part + noise_part
    return out
