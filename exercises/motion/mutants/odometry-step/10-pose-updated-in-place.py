# mistake: writes the new pose into `pose` and returns it, so the caller's pose moves (and a tuple cannot be written)
import math


def odometry_step(pose, u):
    rot1, trans, rot2 = u
    pose[0] += trans * math.cos(pose[2] + rot1)
    pose[1] += trans * math.sin(pose[2] + rot1)
    pose[2] += rot1 + rot2
    return pose
