# method: whitened innovations as complex numbers; best-so-far starts at the gate itself
def nearest_neighbour(z, landmarks, s00, s11, gate):
    zc = complex(z[0] / s00 ** 0.5, z[1] / s11 ** 0.5)
    best, best_d2 = -1, gate
    for j in range(len(landmarks)):
        hc = complex(landmarks[j][0] / s00 ** 0.5, landmarks[j][1] / s11 ** 0.5)
        d2 = abs(zc - hc) ** 2
        if d2 < best_d2:
            best, best_d2 = j, d2
    return best
