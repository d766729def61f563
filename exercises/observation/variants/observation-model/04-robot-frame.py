# method: rotate the offset into the robot frame by hand, then atan2 there; wrap with remainder
import math


def observation_model(xr, yr, thr, xj, yj):
    dx, dy = xj - xr, yj - yr
    c, s = math.cos(thr), math.sin(thr)
    ahead = c * dx + s * dy
    left = -s * dx + c * dy
    return (ahead ** 2 + left ** 2) ** 0.5, math.remainder(math.atan2(left, ahead), 2 * math.pi)
