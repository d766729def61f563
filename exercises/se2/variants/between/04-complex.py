# method: positions as complex numbers, rotation by multiplying with exp(-i theta)
import cmath


def between(a, b):
    offset = complex(b[0] - a[0], b[1] - a[1]) * cmath.exp(-1j * a[2])
    turn = cmath.phase(cmath.exp(1j * (b[2] - a[2])))
    return [offset.real, offset.imag, turn]
