"""
view: the review page of ``inertia-kit view``, every link's inertia drawn over its geometry.
At the level of ``fill``: it may use lint, report and every layer below; ``cli`` calls it.

- ``scene``: ``build_scene(path, ...)``, the page's data (the scene contract): the robot linted
  as ``inertia-lint`` lints it, each link with its drawing, its declared and geometry-derived
  mass properties as equivalent boxes, and its findings.
- ``boxes``: the equivalent uniform box of mass properties (principal axes and sides), and the
  link axis each principal axis lies along (the panel's "0.0002 along x").
- ``pose``: each link's world frame in the zero pose.
- ``display_meshes``: each shape as a triangle mesh in its own frame, distinct meshes carried
  once, decimated for display over a triangle budget.
- ``page``: ``render_page(scene)``, the one self-contained HTML file (a strict CSP, the scene as
  JSON, the vendored three.js and our scripts inline: ``assets/``, re-vendored by
  ``scripts/vendor_three.py``).
- ``screenshot``: the page in headless Chromium over the DevTools pipe: a PNG (``--png``), and
  for the tests its errors, its box positions and every URL it asked for.
"""
