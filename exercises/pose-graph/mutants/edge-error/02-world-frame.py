# mistake: compares z with the world-frame offset xj - xi
import math

def edge_error(xi, xj, z):
    return xj[0] - xi[0] - z[0], xj[1] - xi[1] - z[1], xj[2] - xi[2] - z[2]
