# method: multiply the odds (e^l times p_s / (1 - p_s)), then log of the odds and odds / (1 + odds)
import math


def log_odds_update(current_log_odds, sensor_prob):
    odds = math.exp(current_log_odds) * sensor_prob / (1 - sensor_prob)
    return (math.log(odds), odds / (1 + odds))
