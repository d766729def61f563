# mistake: skips candidates more than 3 m away in range before computing d2 (a fixed pre-gate; with s00 = 4 m2 an innovation of 3.5 m is well inside the gate)
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best, best_d2 = -1, float("inf")
    for j, h in enumerate(landmarks):
        if abs(z[0] - h[0]) > 3.0:
            continue
        d2 = (z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11
        if d2 < gate and d2 < best_d2:
            best, best_d2 = j, d2
    return best
