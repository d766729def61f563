# mistake: the diagonal accumulates but the off-diagonal cells are assigned, so a pair measured twice keeps only its last -w
def build_omega(n, edges):
    omega = [[0.0] * n for _ in range(n)]
    for i, j, w in edges:
        omega[i][i] += w
        omega[j][j] += w
        omega[i][j] = -w
        omega[j][i] = -w
    return omega
