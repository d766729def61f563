# mistake: multiplies the probabilities (p * p_s) instead of adding log-odds
import math


def log_odds_update(current_log_odds, sensor_prob):
    p = 1 / (1 + math.exp(-current_log_odds)) * sensor_prob
    return math.log(p / (1 - p)), p
