# mistake: returns e^l' (the odds) as the probability
import math


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + math.log(sensor_prob / (1 - sensor_prob))
    return l, math.exp(l)
