# mistake: one-sided finite differences with a step of 1e-4 (not accurate to 1e-6)
import math


def _h(x, y, t, lx, ly):
    c, s = math.cos(t), math.sin(t)
    return (c * (lx - x) + s * (ly - y), -s * (lx - x) + c * (ly - y))


def landmark_jacobian(pose, landmark):
    v = [float(pose[0]), float(pose[1]), float(pose[2]), float(landmark[0]), float(landmark[1])]
    base = _h(*v)
    step = 1e-4
    jac = [[0.0] * 5 for _ in range(2)]
    for k in range(5):
        w = list(v)
        w[k] += step
        moved = _h(*w)
        for r in range(2):
            jac[r][k] = (moved[r] - base[r]) / step
    return jac
