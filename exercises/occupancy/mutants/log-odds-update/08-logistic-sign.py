# mistake: 1 / (1 + e^l) instead of 1 / (1 + e^-l): the probability of being free
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return l, 1 / (1 + math.exp(l))
