"""
URDF and xacro: the reader (:mod:`.reader`: plain URDF parsed, xacro expanded by the real ROS
xacro in a bounded sandbox, :mod:`.xacro_expand`), ``$(find)`` and ``package://`` without ROS
(:mod:`.packages`), and the ``<inertial>`` block as text (:mod:`.inertial_xml`).
"""
