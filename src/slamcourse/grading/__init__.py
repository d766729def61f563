"""Grading learners' functions: property tests drawn and judged in the trusted parent.

- :mod:`.returns`: what a function must return, and comparing a returned value with the reference;
- :mod:`.strategies`: Hypothesis strategies from an exercise's ``arguments``;
- :mod:`.properties`: the property-test run that turns a callee's answers into a verdict.
"""
