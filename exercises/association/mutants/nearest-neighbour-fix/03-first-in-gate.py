# mistake: returns the first candidate inside the gate, not the best one
def nearest_neighbour(z, landmarks, s00, s11, gate):
    for j, (r, b) in enumerate(landmarks):
        if (z[0] - r) ** 2 / s00 + (z[1] - b) ** 2 / s11 < gate:
            return j
    return -1
