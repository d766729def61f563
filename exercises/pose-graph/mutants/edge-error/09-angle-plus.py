# mistake: adds the measured turn instead of subtracting it: theta_j - theta_i + theta_z
import math

def edge_error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    mx, my = c * dx + s * dy, -s * dx + c * dy
    cz, sz = math.cos(z[2]), math.sin(z[2])
    ux, uy = mx - z[0], my - z[1]
    return cz * ux + sz * uy, -sz * ux + cz * uy, xj[2] - xi[2] + z[2]
