# mistake: returns the nearest candidate even outside the gate
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d2 = float("inf")
    for j, predicted in enumerate(landmarks):
        d2 = (z[0] - predicted[0]) ** 2 / s00 + (z[1] - predicted[1]) ** 2 / s11
        if d2 < best_d2:
            best_index = j
            best_d2 = d2
    return best_index
