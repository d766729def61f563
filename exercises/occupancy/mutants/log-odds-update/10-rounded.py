# mistake: both values rounded to 3 decimals "for display"
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return round(l, 3), round(1 / (1 + math.exp(-l)), 3)
