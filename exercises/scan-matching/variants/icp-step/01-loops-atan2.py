# method: plain Python loops for the search (strict < keeps the first minimum) and the closed-form sums
import math


def icp_step(P, Q):
    pairs = []
    for px, py in P:
        best, best_d = None, None
        for qx, qy in Q:
            d = (px - qx) ** 2 + (py - qy) ** 2
            if best_d is None or d < best_d:
                best, best_d = (qx, qy), d
        pairs.append(best)
    n = len(P)
    pmx = sum(p[0] for p in P) / n
    pmy = sum(p[1] for p in P) / n
    qmx = sum(q[0] for q in pairs) / n
    qmy = sum(q[1] for q in pairs) / n
    s = c = 0.0
    for (px, py), (qx, qy) in zip(P, pairs):
        ax, ay, bx, by = px - pmx, py - pmy, qx - qmx, qy - qmy
        s += ax * by - ay * bx
        c += ax * bx + ay * by
    theta = math.atan2(s, c)
    tx = qmx - (math.cos(theta) * pmx - math.sin(theta) * pmy)
    ty = qmy - (math.sin(theta) * pmx + math.cos(theta) * pmy)
    return [theta, tx, ty]
