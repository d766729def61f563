# mistake: off by one, range(hit_index + 1): the hit cell is marked free, never occupied
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index + 1):
        out[k] += l_free
    return out
