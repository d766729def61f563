# mistake: the listing's bug left in: Euclidean nu . nu ranks and gates the candidates
def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d2 = float("inf")
    for j, predicted in enumerate(landmarks):
        nu = [z[0] - predicted[0], z[1] - predicted[1]]
        d2 = nu[0] ** 2 + nu[1] ** 2
        if d2 < gate and d2 < best_d2:
            best_index = j
            best_d2 = d2
    return best_index
