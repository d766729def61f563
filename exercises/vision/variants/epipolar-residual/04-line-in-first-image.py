# method: the epipolar line of x' in image 1 (E^T x'), dotted with x, in plain Python
def epipolar_residual(E, x, x2):
    line = [sum(E[i][k] * x2[i] for i in range(3)) for k in range(3)]
    return sum(line[k] * x[k] for k in range(3))
