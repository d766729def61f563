def nearest_neighbour(z, landmarks, s00, s11, gate):
    """Index of the landmark that best explains measurement z, or -1 for a new landmark.

    z:         measurement [range (m), bearing (rad)]
    landmarks: list of predicted measurements [range (m), bearing (rad)], one per candidate
    s00, s11:  variances of the range and bearing innovations (m^2, rad^2), S = diag(s00, s11)
    gate:      threshold on the squared Mahalanobis distance d^2 (e.g. 5.99)

    Returns an int: the candidate with the smallest d^2 among those with d^2 < gate, else -1.
    This version has a bug (see the previous exercise): fix it.
    """
    best_index = -1
    best_d2 = float("inf")
    for j, predicted in enumerate(landmarks):
        nu = [z[0] - predicted[0], z[1] - predicted[1]]
        d2 = nu[0] ** 2 + nu[1] ** 2
        if d2 < gate and d2 < best_d2:
            best_index = j
            best_d2 = d2
    return best_index
