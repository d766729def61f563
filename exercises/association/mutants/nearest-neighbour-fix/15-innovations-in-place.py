# mistake: turns each candidate into its innovation in place, so the caller's list of landmarks is changed
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best, best_d2 = -1, float("inf")
    for j, h in enumerate(landmarks):
        h[0] = z[0] - h[0]
        h[1] = z[1] - h[1]
        d2 = h[0] ** 2 / s00 + h[1] ** 2 / s11
        if d2 < gate and d2 < best_d2:
            best, best_d2 = j, d2
    return best
