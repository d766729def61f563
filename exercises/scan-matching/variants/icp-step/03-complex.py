# method: points as complex numbers; nearest by abs(), rotation as the phase of Σ conj(p') q'
import cmath


def icp_step(P, Q):
    p = [complex(x, y) for x, y in P]
    q = [complex(x, y) for x, y in Q]
    m = [min(q, key=lambda z: abs(z - w)) for w in p]  # min keeps the first of equal keys
    pm = sum(p) / len(p)
    mm = sum(m) / len(m)
    theta = cmath.phase(sum((a - pm).conjugate() * (b - mm) for a, b in zip(p, m)))
    t = mm - cmath.exp(1j * theta) * pm
    return [theta, t.real, t.imag]
