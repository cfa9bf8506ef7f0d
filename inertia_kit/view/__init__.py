"""
The review page (``inertia-kit view``): every link's declared inertia and the one its geometry
implies, drawn as equivalent boxes over the robot, with the findings beside them, in one
self-contained offline HTML file (:mod:`.page`), and a PNG of it where a headless Chromium is
installed (:mod:`.screenshot`). At the level of ``fill``: it may import lint, report and below.
"""
