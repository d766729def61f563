# mistake: the squared residual (the cost a least-squares fit would sum), not the residual
def epipolar_residual(E, x, x2):
    Ex = [sum(E[i][k] * x[k] for k in range(3)) for i in range(3)]
    r = sum(x2[i] * Ex[i] for i in range(3))
    return r * r
