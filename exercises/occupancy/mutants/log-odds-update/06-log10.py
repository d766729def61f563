# mistake: base-10 logarithm for the reading's log-odds, natural exp for the probability
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log10(sensor_prob / (1 - sensor_prob))
    return l, 1 / (1 + math.exp(-l))
