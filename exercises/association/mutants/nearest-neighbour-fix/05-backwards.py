# mistake: scans the list from the end (newest landmarks first): on an exact tie the last one wins
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d2 = gate
    for j in range(len(landmarks) - 1, -1, -1):
        r, b = landmarks[j]
        d2 = (z[0] - r) ** 2 / s00 + (z[1] - b) ** 2 / s11
        if d2 < best_d2:
            best_index, best_d2 = j, d2
    return best_index
