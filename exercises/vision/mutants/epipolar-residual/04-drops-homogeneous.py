# mistake: the loops run over u and v only (range(2)), dropping the homogeneous coordinate
def epipolar_residual(E, x, x2):
    total = 0.0
    for i in range(2):
        for k in range(2):
            total += x2[i] * E[i][k] * x[k]
    return total
