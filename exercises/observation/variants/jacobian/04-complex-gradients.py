# method: complex numbers: with d = Δx + iΔy, grad r = d/|d| and grad φ = i·d/|d|² (as x + iy)
def range_bearing_jacobian(xr, yr, thr, xj, yj):
    d = complex(xj - xr, yj - yr)
    g_r = d / abs(d)
    g_phi = 1j * d / abs(d) ** 2
    return [
        [-g_r.real, -g_r.imag, 0.0, g_r.real, g_r.imag],
        [-g_phi.real, -g_phi.imag, -1.0, g_phi.real, g_phi.imag],
    ]
