# mistake: [[0.0] * n] * n makes every row the same list object
def build_omega(n, edges):
    omega = [[0.0] * n] * n
    for i, j, w in edges:
        omega[i][i] += w
        omega[j][j] += w
        omega[i][j] -= w
        omega[j][i] -= w
    return omega
