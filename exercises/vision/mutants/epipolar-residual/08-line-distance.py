# mistake: returns the distance from x' to the epipolar line E x (residual / |(Ex)_12|), not the residual
import math


def epipolar_residual(E, x, x2):
    a, b, c = (sum(E[i][k] * x[k] for k in range(3)) for i in range(3))
    return (a * x2[0] + b * x2[1] + c * x2[2]) / math.hypot(a, b)
