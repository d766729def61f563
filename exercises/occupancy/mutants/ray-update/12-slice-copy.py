# mistake: copies the row with log_odds[:], which is a tuple for a tuple and a view of the caller's cells for a numpy array
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = log_odds[:]
    for k in range(hit_index):
        out[k] = out[k] + l_free
    out[hit_index] = out[hit_index] + l_occ
    return out
