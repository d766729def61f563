"""The batch grader: a class's submissions graded by the engine, exported to grading platforms.

``submission`` (what a learner hands in, read safely), ``grade`` (each submission in a fresh
engine; hidden checks), ``exporters`` (Gradescope, Exercism, PrairieLearn, JUnit, gradebook
CSV), ``stats`` (solve rates, attempts, misconceptions), ``bundle`` (the Gradescope autograder
zip) and ``prairielearn`` (the external-grader entry point). See docs/submissions.md.
"""
