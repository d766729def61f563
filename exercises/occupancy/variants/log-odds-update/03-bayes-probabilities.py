# method: Bayes' rule on probabilities (normalised product), then converted back to log-odds
import math


def log_odds_update(current_log_odds, sensor_prob):
    p = 1 / (1 + math.exp(-current_log_odds))
    occupied = p * sensor_prob
    free = (1 - p) * (1 - sensor_prob)
    new_p = occupied / (occupied + free)
    return [math.log(occupied / free), new_p]
