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
)
NOT_FOR_WARM_CACHE = ("trimesh", "manifold3d", "collada")
