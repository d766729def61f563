# mistake: the squared distance in metres compared with the gate (Euclidean, not Mahalanobis)
import math


def loop_candidates(poses, marginals, cross, gap, confidence):
    k = len(poses) - 1
    gate = -2.0 * math.log(1.0 - confidence)
    xk, yk = float(poses[k][0]), float(poses[k][1])
    out = []
    for i in range(k - int(gap) + 1):
        dx, dy = xk - float(poses[i][0]), yk - float(poses[i][1])
        if dx * dx + dy * dy <= gate:
            out.append(i)
    return out
