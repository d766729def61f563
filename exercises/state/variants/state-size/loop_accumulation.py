# method: grows the state one landmark at a time and sums a row of n entries n times
def state_size(pose_dim, landmark_dim, num_landmarks):
    n = pose_dim
    for _ in range(num_landmarks):
        n += landmark_dim
    entries = 0
    for _row in range(n):
        entries += n
    return [n, entries]
