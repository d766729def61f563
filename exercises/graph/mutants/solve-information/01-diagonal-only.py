# mistake: mu_i = xi_i / Omega_ii, ignoring the off-diagonal couplings
def solve_information(omega, xi):
    return [xi[i] / omega[i][i] for i in range(len(xi))]
