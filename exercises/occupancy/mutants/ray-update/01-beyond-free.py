# mistake: every cell except the hit gets l_free, including the cells behind the obstacle
def update_ray(log_odds, hit_index, l_occ, l_free):
    out = [v + l_free for v in log_odds]
    out[hit_index] = log_odds[hit_index] + l_occ
    return out
