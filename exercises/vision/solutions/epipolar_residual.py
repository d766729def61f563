def epipolar_residual(E, x, x2):
    Ex = [sum(E[i][k] * x[k] for k in range(3)) for i in range(3)]
    return sum(x2[i] * Ex[i] for i in range(3))
