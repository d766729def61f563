# method: numpy, log(p) - log1p(-p) for the log-odds and 0.5 (1 + tanh(l / 2)) for the logistic
import numpy as np


def log_odds_update(current_log_odds, sensor_prob):
    l = current_log_odds + np.log(sensor_prob) - np.log1p(-sensor_prob)
    return np.array([l, 0.5 * (1 + np.tanh(l / 2))])
