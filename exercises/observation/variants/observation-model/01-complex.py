# method: complex numbers: rotate the offset by e^{-i thr}; abs and phase give range and bearing
import cmath


def observation_model(xr, yr, thr, xj, yj):
    local = complex(xj - xr, yj - yr) * cmath.exp(-1j * thr)
    return abs(local), cmath.phase(local)
