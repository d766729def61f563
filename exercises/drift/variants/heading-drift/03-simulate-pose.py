# method: simulate the robot: turn by heading_rate, wrap the heading into [0, 2π), step forward
import math


def lateral_drift(step_length, heading_rate, steps):
    heading = 0.0
    y = 0.0
    for _ in range(steps):
        heading = (heading + heading_rate) % (2 * math.pi)
        y += step_length * math.sin(heading)
    return y
