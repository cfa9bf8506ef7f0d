"""
analysis: what a robot's values and geometry mean, per link, for lint, fill and report.

- ``links``: :class:`~inertia_kit.analysis.links.LinkAnalysis` and ``RobotAnalysis``, the entry
  point (``analyse(robot)``): each link's declared values, geometry and bounds, computed lazily,
  and the robot's fixed-joint groups.
- ``declared``: the declared ``<inertial>`` as mass properties.
- ``geometry``: shapes evaluated as solids at unit density, and their union.
- ``bounds``: convex hulls of the geometry and the hard moment bounds they set.
- ``firmness``: whether a value beyond a bound is certainly impossible (rounding of the
  written numbers, mesh facets, collision or visual geometry).
- ``tensors``: comparing two tensors about every axis; when a principal moment is zero.
- ``expected``: the geometry's tensor as a link's ``<inertia>`` would write it.
- ``describe``: a shape in words, for messages and for the report table.
- ``principal_axes``: the declared principal axes against the geometry's, judged by how far
  apart the moments are (IN069).
- ``forensics``: why a declared tensor disagrees with its geometry.
"""
