# mistake: subtracts l_free ("free lowers the log-odds"), but l_free is already negative
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index):
        out[k] -= l_free
    out[hit_index] += l_occ
    return out
