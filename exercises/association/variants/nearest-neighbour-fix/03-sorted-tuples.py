# method: sort (d2, index) tuples (ties go to the smaller index), then gate the best one
import math


def nearest_neighbour(z, landmarks, s00, s11, gate):
    ranked = sorted(
        (math.hypot((z[0] - r) / math.sqrt(s00), (z[1] - b) / math.sqrt(s11)) ** 2, j)
        for j, (r, b) in enumerate(landmarks)
    )
    if ranked and ranked[0][0] < gate:
        return ranked[0][1]
    return -1
