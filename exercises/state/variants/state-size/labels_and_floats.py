# method: lists a label per state entry, and returns integer-valued floats
def state_size(pose_dim, landmark_dim, num_landmarks):
    labels = [f"pose{i}" for i in range(pose_dim)]
    for j in range(num_landmarks):
        labels += [f"m{j}.{k}" for k in range(landmark_dim)]
    n = float(len(labels))
    return (n, n**2)
