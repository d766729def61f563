def update_ray(log_odds, hit_index, l_occ, l_free):
    """Log-odds update of the cells along one range beam.

    log_odds:  list of the cells' log-odds, in the order the beam crosses them (length n >= 1).
    hit_index: index (0 <= hit_index < n) of the cell where the beam hit an obstacle.
    l_occ:     log-odds added to the hit cell (positive).
    l_free:    log-odds added to each cell the beam crossed before the hit (negative).

    Returns the updated row, length n; cells after the hit are unchanged.
    """
    raise NotImplementedError("TODO: return the updated list of log-odds")
