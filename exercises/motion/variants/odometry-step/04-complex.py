# method: position as a complex number moved by trans * exp(i (theta + rot1))
import cmath


def odometry_step(pose, u):
    x, y, theta = pose
    rot1, trans, rot2 = u
    p = complex(x, y) + trans * cmath.exp(1j * (theta + rot1))
    return p.real, p.imag, theta + rot1 + rot2
