# method: Gaussian elimination without pivoting and back substitution in plain Python (Omega is SPD)
def solve_information(omega, xi):
    n = len(xi)
    A = [[float(v) for v in row] + [float(b)] for row, b in zip(omega, xi)]
    for c in range(n):
        for r in range(c + 1, n):
            f = A[r][c] / A[c][c]
            A[r] = [a - f * p for a, p in zip(A[r], A[c])]
    mu = [0.0] * n
    for r in reversed(range(n)):
        mu[r] = (A[r][n] - sum(A[r][k] * mu[k] for k in range(r + 1, n))) / A[r][r]
    return tuple(mu)
