# mistake: sorts the candidate list in place by distance and returns the position in the sorted list
def nearest_neighbour(z, landmarks, s00, s11, gate):
    def d2(h):
        return (z[0] - h[0]) ** 2 / s00 + (z[1] - h[1]) ** 2 / s11

    landmarks.sort(key=d2)
    if landmarks and d2(landmarks[0]) < gate:
        return 0
    return -1
