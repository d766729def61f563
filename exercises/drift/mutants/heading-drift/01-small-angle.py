# mistake: sin x ≈ x for every step (the small-angle approximation)
def lateral_drift(step_length, heading_rate, steps):
    return sum(step_length * heading_rate * k for k in range(1, steps + 1))
