import math


def log_odds_update(current_log_odds, sensor_prob):
    new_l = current_log_odds + math.log(sensor_prob) - math.log(1 - sensor_prob)
    new_p = math.exp(new_l) / (1 + math.exp(new_l))
    return new_l, new_p
