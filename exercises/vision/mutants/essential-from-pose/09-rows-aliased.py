# mistake: [[0.0] * 3] * 3 makes the three rows of E one list
def essential_matrix(t, R):
    tx, ty, tz = t
    S = [[0, -tz, ty], [tz, 0, -tx], [-ty, tx, 0]]
    E = [[0.0] * 3] * 3
    for i in range(3):
        for j in range(3):
            E[i][j] = sum(S[i][k] * R[k][j] for k in range(3))
    return E
