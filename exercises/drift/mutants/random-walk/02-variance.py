# mistake: returns the variance k * sigma**2 (m^2) instead of its square root
def random_walk_error(sigma, steps):
    return steps * sigma ** 2
