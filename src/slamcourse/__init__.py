"""slamcourse: a course engine and auto-grader that teaches classical SLAM from zero."""

__version__ = "0.1.0"
