"""
MJCF (MuJoCo's XML): the reader (:mod:`.reader`, as MuJoCo's compiler reads a model: includes,
default classes, the compiler's settings, every orientation form, replicates, attached models)
and the writer of an ``<inertial>`` element (:mod:`.writer`).
"""
