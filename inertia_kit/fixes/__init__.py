"""
Fixes as a xacro author would write them: where a link's ``<inertial>`` values are written, and
the text edits that change them there.

Below ``lint`` (whose rules attach fixes to findings) and ``fill`` (which asks for values from
geometry and its mass inputs), so both write through one path. :mod:`.sites` finds the place of
each link's values and the edits there, in the :mod:`.files` a fix may touch, reading xacro
macros with :mod:`.xacro_macros`.
"""
