"""
What a fix writes, whatever the format: the mass each link gets (:mod:`.masses`: the mass
inputs, ``MassChoice``) and why a link gets no fix (:mod:`.refusals`). Where the values are
written is the format's writer's (:mod:`inertia_kit.description.placement`).

Below ``lint`` (whose rules attach fixes to findings) and ``fill`` (which asks for values from
geometry and its mass inputs), so both write through one path.
"""
