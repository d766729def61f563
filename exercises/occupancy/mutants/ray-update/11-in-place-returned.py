# mistake: updates the caller's row in place and returns it
def update_ray(log_odds, hit_index, l_occ, l_free):
    for k in range(hit_index):
        log_odds[k] += l_free
    log_odds[hit_index] += l_occ
    return log_odds
