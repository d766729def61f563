# mistake: adds log(p_s) instead of the reading's log-odds log(p_s / (1 - p_s))
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob)
    return l, 1 / (1 + math.exp(-l))
