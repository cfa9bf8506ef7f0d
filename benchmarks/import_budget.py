"""
What a lint run must not import, checked by `benchmarks/lint.py` and by
`tests/cli/test_cli_import_budget.py` (one list for both; no imports here, so the tests can
load it by path).
"""

#: what no run may import: a plain URDF needs no xacro (nor what it pulls in), and a warm
#: cache reads no mesh, so needs no mesh library
NOT_FOR_PLAIN_URDF = (
    "inertia_kit.description.urdf.xacro_expand",
    "xacro",
    "yaml",
    "urllib.request",
    "email",
    "http.client",
    "ssl",
    # a file given by name with no exclude patterns compiles none; stdin's helpers wait for `-`
    "pathspec",
    "secrets",
    # issue 23: what only a misspelling, a mesh, a repository scan or a suppression comment
    # needs (difflib's suggestions, the mesh readers and unions, the include cache, the markup
    # scanner); and hashlib, which loads OpenSSL: description.reads takes BLAKE2 from _blake2
    "difflib",
    "hashlib",
    "inertia_kit.analysis.mesh_units",
    "inertia_kit.physics.mesh_formats",
    "inertia_kit.physics.manifolds",
    "inertia_kit.lint.include_cache",
    "inertia_kit.lint.markup",
    # the machine-read formats' encoder: a run that prints text needs none
    "json",
    # the forensic hypotheses (and the search that tries them): a robot whose tensors agree
    # with their geometry has no slip to explain
    "inertia_kit.analysis.forensics.diagnosis",
    "inertia_kit.analysis.forensics.candidate",
    "inertia_kit.analysis.forensics.flipped_signs",
    "inertia_kit.analysis.forensics.other_axes",
    "inertia_kit.analysis.forensics.other_point",
    "inertia_kit.analysis.forensics.transposed",
    "inertia_kit.analysis.forensics.unit_slip",
)
NOT_FOR_WARM_CACHE = ("trimesh", "manifold3d", "collada")
