"""Reference implementations of the course's mathematics."""
