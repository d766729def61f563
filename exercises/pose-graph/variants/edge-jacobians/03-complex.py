# method: complex numbers; d/dtheta of w * exp(-i theta) is -i w exp(-i theta)
import cmath


def edge_jacobians(xi, xj, z):
    rot = cmath.exp(-1j * (xi[2] + z[2]))  # Rz^T Ri^T as one complex factor
    offset = complex(xj[0] - xi[0], xj[1] - xi[1])
    d_theta = -1j * offset * rot
    # a complex factor r acting on (x, y) is the matrix [[Re r, -Im r], [Im r, Re r]]
    R = [[rot.real, -rot.imag], [rot.imag, rot.real]]
    A = [
        [-R[0][0], -R[0][1], d_theta.real],
        [-R[1][0], -R[1][1], d_theta.imag],
        [0.0, 0.0, -1.0],
    ]
    B = [[R[0][0], R[0][1], 0.0], [R[1][0], R[1][1], 0.0], [0.0, 0.0, 1.0]]
    return [a + b for a, b in zip(A, B)]
