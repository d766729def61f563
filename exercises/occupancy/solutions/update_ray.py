def update_ray(log_odds, hit_index, l_occ, l_free):
    updated = []
    for k, value in enumerate(log_odds):
        if k < hit_index:
            updated.append(value + l_free)
        elif k == hit_index:
            updated.append(value + l_occ)
        else:
            updated.append(value)
    return updated
