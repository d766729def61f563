# mistake: off by one the other way, range(hit_index - 1): the cell just before the hit is not marked free
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index - 1):
        out[k] += l_free
    out[hit_index] += l_occ
    return out
