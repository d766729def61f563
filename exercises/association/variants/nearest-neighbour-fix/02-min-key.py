# method: min() with a key over the gated (index, d2) pairs, default -1
def nearest_neighbour(z, landmarks, s00, s11, gate):
    scored = [
        (j, (z[0] - r) ** 2 / s00 + (z[1] - b) ** 2 / s11) for j, (r, b) in enumerate(landmarks)
    ]
    inside = [(j, d2) for j, d2 in scored if d2 < gate]
    if not inside:
        return -1
    return min(inside, key=lambda pair: pair[1])[0]
