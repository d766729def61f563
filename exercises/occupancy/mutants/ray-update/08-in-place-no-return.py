# mistake: updates the list in place and returns nothing
def update_ray(log_odds, hit_index, l_occ, l_free):
    for k in range(hit_index):
        log_odds[k] += l_free
    log_odds[hit_index] += l_occ
