# mistake: the columns t x R[:, k] written as rows, i.e. E transposed
def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def essential_matrix(t, R):
    return [cross(t, [R[0][k], R[1][k], R[2][k]]) for k in range(3)]
