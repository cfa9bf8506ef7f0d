"""
``inertia-fill``: write the ``<inertial>`` blocks links need, as text edits on the files.

:mod:`.plan` makes a plan of one file and applies it: :mod:`.policy` chooses the links, their
masses and the refusals (with :mod:`.materials`, the ``--material`` densities);
:mod:`inertia_kit.fixes` writes each link's values where its author would; :mod:`.output` is
``-o OUT``; :mod:`.fragments` fills a given fragment through the robots that include it, and
:mod:`.shared` keeps those robots from writing different values into one element.
"""
