# mistake: '=' instead of '+=': a pose touched by several edges keeps only the last one
def build_omega(n, edges):
    omega = [[0.0] * n for _ in range(n)]
    for i, j, w in edges:
        omega[i][i] = w
        omega[j][j] = w
        omega[i][j] = -w
        omega[j][i] = -w
    return omega
