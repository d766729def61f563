# mistake: Gaussian elimination that updates the matrix rows but forgets to update xi
def solve_information(omega, xi):
    n = len(xi)
    A = [[float(v) for v in row] for row in omega]
    b = [float(v) for v in xi]
    for c in range(n):
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            for k in range(c, n):
                A[r][k] -= f * A[c][k]
    mu = [0.0] * n
    for r in reversed(range(n)):
        mu[r] = (b[r] - sum(A[r][k] * mu[k] for k in range(r + 1, n))) / A[r][r]
    return mu
