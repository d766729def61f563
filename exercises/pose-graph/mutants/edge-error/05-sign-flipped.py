# mistake: returns z minus the predicted relative pose (both signs reversed)
import math

def edge_error(xi, xj, z):
    dx, dy = xj[0] - xi[0], xj[1] - xi[1]
    c, s = math.cos(xi[2]), math.sin(xi[2])
    mx, my = c * dx + s * dy, -s * dx + c * dy
    cz, sz = math.cos(z[2]), math.sin(z[2])
    ux, uy = z[0] - mx, z[1] - my
    return cz * ux + sz * uy, -sz * ux + cz * uy, z[2] - (xj[2] - xi[2])
