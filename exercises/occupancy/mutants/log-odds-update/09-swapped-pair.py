# mistake: returns (probability, log-odds) instead of (log-odds, probability)
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return 1 / (1 + math.exp(-l)), l
