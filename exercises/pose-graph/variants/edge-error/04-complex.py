# method: complex numbers: rotate the offset by exp(-i theta_i), then subtract tz and rotate by exp(-i theta_z)
import cmath


def edge_error(xi, xj, z):
    local = complex(xj[0] - xi[0], xj[1] - xi[1]) * cmath.exp(-1j * xi[2])
    e = (local - complex(z[0], z[1])) * cmath.exp(-1j * z[2])
    turn = cmath.phase(cmath.exp(1j * (xj[2] - xi[2] - z[2])))
    return e.real, e.imag, turn
