# mistake: subtracts z component by component from xi^-1 (+) xj
import math

def edge_error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    return c * dx + s * dy - z[0], -s * dx + c * dy - z[1], xj[2] - xi[2] - z[2]
