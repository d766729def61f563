# method: plain Python floats: the 2x6 Jacobian and 2x2 covariance by sums, inverse by formula
import math


def block6(mi, cik, mk):
    """The 6x6 joint covariance as nested lists of floats."""
    rows = []
    for a in range(3):
        rows.append([float(mi[a][b]) for b in range(3)] + [float(cik[a][b]) for b in range(3)])
    for a in range(3):
        rows.append([float(cik[b][a]) for b in range(3)] + [float(mk[a][b]) for b in range(3)])
    return rows


def loop_candidates(poses, marginals, cross, gap, confidence):
    n = len(poses)
    k = n - 1
    gate = -2.0 * math.log(1.0 - float(confidence))
    xk, yk = float(poses[k][0]), float(poses[k][1])
    out = []
    i = 0
    while i <= k - int(gap):
        xi, yi, ti = (float(v) for v in poses[i])
        c, s = math.cos(ti), math.sin(ti)
        dx, dy = xk - xi, yk - yi
        rx, ry = c * dx + s * dy, -s * dx + c * dy
        jx = [-c, -s, ry, c, s, 0.0]  # d r_x: -s dx + c dy is r_y
        jy = [s, -c, -rx, -s, c, 0.0]  # d r_y: -c dx - s dy is -r_x
        p = block6(marginals[i], cross[i], marginals[k])
        pjx = [sum(p[a][b] * jx[b] for b in range(6)) for a in range(6)]
        pjy = [sum(p[a][b] * jy[b] for b in range(6)) for a in range(6)]
        sxx = sum(jx[a] * pjx[a] for a in range(6))
        syy = sum(jy[a] * pjy[a] for a in range(6))
        sxy = sum(jx[a] * pjy[a] for a in range(6))
        det = sxx * syy - sxy * sxy
        d2 = (syy * rx * rx - 2 * sxy * rx * ry + sxx * ry * ry) / det
        if d2 <= gate:
            out.append(i)
        i += 1
    return out
