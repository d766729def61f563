# mistake: divides the squared innovations by the standard deviations, not the variances
import math


def nearest_neighbour(z, landmarks, s00, s11, gate):
    best_index = -1
    best_d2 = float("inf")
    for j, predicted in enumerate(landmarks):
        nu0, nu1 = z[0] - predicted[0], z[1] - predicted[1]
        d2 = nu0 ** 2 / math.sqrt(s00) + nu1 ** 2 / math.sqrt(s11)
        if d2 < gate and d2 < best_d2:
            best_index, best_d2 = j, d2
    return best_index
