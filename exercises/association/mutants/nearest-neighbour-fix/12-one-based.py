# mistake: returns a 1-based landmark number (enumerate(..., start=1))
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d2 = float("inf")
    for j, predicted in enumerate(landmarks, start=1):
        d2 = (z[0] - predicted[0]) ** 2 / s00 + (z[1] - predicted[1]) ** 2 / s11
        if d2 < gate and d2 < best_d2:
            best_index, best_d2 = j, d2
    return best_index
