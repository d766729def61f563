# method: complex numbers: the angle of Σ conj(p') q' over centred points
import cmath


def align_2d(P, Q):
    p = [complex(x, y) for x, y in P]
    q = [complex(x, y) for x, y in Q]
    pm = sum(p) / len(p)
    qm = sum(q) / len(q)
    z = sum((a - pm).conjugate() * (b - qm) for a, b in zip(p, q))
    theta = cmath.phase(z)
    t = qm - cmath.exp(1j * theta) * pm
    return [theta, t.real, t.imag]
