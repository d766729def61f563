# method: every entry written out with cos and sin, as nested lists
import math


def landmark_jacobian(pose, landmark):
    c, s = math.cos(pose[2]), math.sin(pose[2])
    dx, dy = landmark[0] - pose[0], landmark[1] - pose[1]
    return [
        [-c, -s, -s * dx + c * dy, c, s],
        [s, -c, -c * dx - s * dy, -s, c],
    ]
