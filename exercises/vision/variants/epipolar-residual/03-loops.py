# method: plain Python double loop over the nine terms x'_i E_ik x_k
def epipolar_residual(E, x, x2):
    total = 0.0
    for i in range(3):
        for k in range(3):
            total += x2[i] * E[i][k] * x[k]
    return total
