# mistake: steps ** (1 // 2) is steps ** 0 == 1 (integer division in the exponent)
def random_walk_error(sigma, steps):
    return sigma * steps ** (1 // 2)
