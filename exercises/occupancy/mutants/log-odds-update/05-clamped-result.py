# mistake: the new log-odds clamped to [-10, 10] (a map's clamping bound, not part of this update)
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    l = max(-10.0, min(10.0, l))
    return l, 1 / (1 + math.exp(-l))
