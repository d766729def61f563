# method: one list comprehension choosing the increment from each cell's position (a tuple out)
def update_ray(log_odds, hit_index, l_occ, l_free):
    return tuple(v + (l_free if k < hit_index else l_occ if k == hit_index else 0)
                 for k, v in enumerate(log_odds))
