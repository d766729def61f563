# mistake: copies the row with log_odds.copy(), which a tuple does not have
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = log_odds.copy()
    for k in range(hit_index):
        out[k] = out[k] + l_free
    out[hit_index] = out[hit_index] + l_occ
    return out
