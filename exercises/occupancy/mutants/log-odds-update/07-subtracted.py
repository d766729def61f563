# mistake: the reading's log-odds subtracted (sign convention log((1 - p) / p))
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log((1 - sensor_prob) / sensor_prob)
    return l, 1 / (1 + math.exp(-l))
