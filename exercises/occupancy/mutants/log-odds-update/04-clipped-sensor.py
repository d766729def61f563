# mistake: the reading clipped to [0.01, 0.99] "to avoid infinities": a 0.999 LiDAR hit counts as 0.99
import numpy as np


def log_odds_update(current_log_odds, sensor_prob):
    p = np.clip(sensor_prob, 0.01, 0.99)
    l = current_log_odds + np.log(p / (1 - p))
    return float(l), float(1 / (1 + np.exp(-l)))
