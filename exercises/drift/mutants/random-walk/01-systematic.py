# mistake: adds the standard deviations (sigma * k), as a bias would add up
def random_walk_error(sigma, steps):
    return sigma * steps
