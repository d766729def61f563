# method: closed form, Rz^T (Ri^T (tj - ti) - tz), angle wrapped with atan2
import math


def edge_error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    ux, uy = c * dx + s * dy - z[0], -s * dx + c * dy - z[1]
    cz, sz = math.cos(z[2]), math.sin(z[2])
    t = xj[2] - xi[2] - z[2]
    return [cz * ux + sz * uy, -sz * ux + cz * uy, math.atan2(math.sin(t), math.cos(t))]
