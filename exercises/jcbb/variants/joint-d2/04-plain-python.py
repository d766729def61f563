# method: plain Python lists: S by explicit sums, then Gaussian elimination on S x = ν
def joint_d2(H, P, R, nu):
    m, n = len(H), len(P)
    HP = [[sum(H[a][i] * P[i][b] for i in range(n)) for b in range(n)] for a in range(m)]
    S = [[sum(HP[a][i] * H[c][i] for i in range(n)) for c in range(m)] for a in range(m)]
    for a in range(0, m, 2):
        for i in range(2):
            for j in range(2):
                S[a + i][a + j] += R[i][j]
    A = [row[:] + [float(nu[a])] for a, row in enumerate(S)]
    for col in range(m):
        piv = max(range(col, m), key=lambda r: abs(A[r][col]))
        A[col], A[piv] = A[piv], A[col]
        for r in range(col + 1, m):
            f = A[r][col] / A[col][col]
            A[r] = [x - f * y for x, y in zip(A[r], A[col])]
    x = [0.0] * m
    for r in reversed(range(m)):
        x[r] = (A[r][m] - sum(A[r][c] * x[c] for c in range(r + 1, m))) / A[r][r]
    return sum(float(nu[a]) * x[a] for a in range(m))
