# method: copy the list, add l_free over range(hit_index), add l_occ at the hit
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index):
        out[k] += l_free
    out[hit_index] += l_occ
    return out
