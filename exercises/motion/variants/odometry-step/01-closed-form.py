# method: the closed form with the intermediate heading named
import math


def odometry_step(pose, u):
    x, y, theta = pose
    rot1, trans, rot2 = u
    heading = theta + rot1
    return [x + trans * math.cos(heading), y + trans * math.sin(heading), heading + rot2]
