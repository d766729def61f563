# method: plain Python cross products, column by column, assembled into a list of rows
def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def essential_matrix(t, R):
    cols = [cross(t, [R[0][k], R[1][k], R[2][k]]) for k in range(3)]
    return [[cols[k][i] for k in range(3)] for i in range(3)]
