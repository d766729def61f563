import math


def log_odds_update(current_log_odds, sensor_prob):
    """Fuse one occupancy reading into a grid cell.

    current_log_odds: the cell's log-odds l = log(p / (1 - p)) before the reading (natural log).
    sensor_prob:      the reading's probability that the cell is occupied (0.001 to 0.999).

    Returns (new_log_odds, new_prob): the log-odds after the reading and the corresponding
    probability of occupancy (between 0 and 1).
    """
    raise NotImplementedError("TODO: return (new_log_odds, new_prob)")
