# method: central finite differences of the error with a step of 1e-6
import math


def _h(x, y, t, lx, ly):
    c, s = math.cos(t), math.sin(t)
    return (c * (lx - x) + s * (ly - y), -s * (lx - x) + c * (ly - y))


def landmark_jacobian(pose, landmark):
    v = [float(pose[0]), float(pose[1]), float(pose[2]), float(landmark[0]), float(landmark[1])]
    step = 1e-6
    jac = [[0.0] * 5 for _ in range(2)]
    for k in range(5):
        hi, lo = list(v), list(v)
        hi[k] += step
        lo[k] -= step
        a, b = _h(*hi), _h(*lo)
        for r in range(2):
            jac[r][k] = (a[r] - b[r]) / (2 * step)
    return jac
