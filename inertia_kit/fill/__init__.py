"""
``inertia-fill``: write the ``<inertial>`` blocks links need, as text edits on the files.

:mod:`.plan` makes a plan of one file and applies it: :mod:`.policy` chooses the links, their
masses and the refusals (with :mod:`.materials`, the ``--material`` densities); :mod:`.sites`
finds where each link's values are written and the edits there, in the :mod:`.files` a fill may
touch, reading xacro macros with :mod:`.xacro_macros`; :mod:`.output` is ``-o OUT``.
"""
