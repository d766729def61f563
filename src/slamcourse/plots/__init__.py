"""Pictures drawn from an exercise variant's own numbers: pure functions, parameters → SVG.

``registry.plot_for`` picks the picture of an exercise; the browser inlines it and
``slamcourse plot ID`` writes it to a file. Nothing here imports numpy or the engine.
"""
