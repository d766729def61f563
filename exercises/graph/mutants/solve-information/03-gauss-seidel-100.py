# mistake: Gauss-Seidel with a fixed 100 sweeps: converged on small graphs, far off on a long chain with a weak prior
def solve_information(omega, xi):
    n = len(xi)
    mu = [0.0] * n
    for _ in range(100):
        for i in range(n):
            s = sum(omega[i][k] * mu[k] for k in range(n) if k != i)
            mu[i] = (xi[i] - s) / omega[i][i]
    return mu
