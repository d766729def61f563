# mistake: the free cells are updated but the hit cell is left unchanged
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index):
        out[k] += l_free
    return out
