# mistake: gates d = sqrt(d2) against a threshold meant for d2
import math


def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d = math.inf
    for j, predicted in enumerate(landmarks):
        d = math.sqrt((z[0] - predicted[0]) ** 2 / s00 + (z[1] - predicted[1]) ** 2 / s11)
        if d < gate and d < best_d:
            best_index, best_d = j, d
    return best_index
