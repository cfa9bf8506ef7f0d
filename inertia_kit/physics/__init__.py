"""
physics: the ground floor, mass properties in SI units, every layer may use it; it never touches
XML.

- ``mass``: :class:`~inertia_kit.physics.mass.MassProperties`, the one value type (mass, COM,
  tensor about the COM), with placement, parallel axis, addition and validity; ``frames``: URDF
  ``xyz``/``rpy`` as transforms.
- ``primitives``: closed forms for boxes, cylinders, spheres, capsules, ellipsoids;
  ``tessellate``: their volume-exact meshes; ``unions`` (with ``manifolds``): overlapping parts
  counted once; ``union_cache``: those of overlapping primitives, cached on disk.
- ``meshes``: mesh files as mass properties (``mesh_formats`` reads them, ``stl`` fast, without
  trimesh, and ``obj_soup`` and ``collada`` as trimesh would, without it, their numbers through
  ``decimal_text``; ``obj_polygons``: an OBJ as MuJoCo reads it; ``mesh_closure`` decides how
  the volume is integrated; ``polyhedra`` and ``volume_moments`` are the integration kernel);
  ``mesh_cache`` (with ``mesh_cache_entries``): the on-disk cache.
- ``formatting``: numbers, vectors and tensors as text; ``tensor_names``: ``ixx``…``izz``.
"""
