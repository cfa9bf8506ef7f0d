"""
Mass-property reports for people: :mod:`.robot` the ``inertia-kit report`` tables of a robot's
links (or of the bodies each engine simulates), :mod:`.mass` the ``inertia-kit mass`` report of
one part.
"""
