# mistake: hit_index read as 1-based: the cell before the hit gets l_occ (and hit_index 0 wraps to the last cell)
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = list(log_odds)
    for k in range(hit_index - 1):
        out[k] += l_free
    out[hit_index - 1] += l_occ
    return out
