"""The package's public surface and its import cost."""

import subprocess
import sys

import inertia_kit


def test_every_export_resolves():
    for name in inertia_kit.__all__:
        assert getattr(inertia_kit, name) is not None


def test_cli_sets_one_blas_thread_before_numpy_and_loads_no_mesh_library():
    code = (
        "import os, sys; os.environ.pop('OPENBLAS_NUM_THREADS', None)\n"
        "import inertia_kit.cli\n"
        "assert 'numpy' not in sys.modules, 'numpy imported at CLI start-up'\n"
        "assert os.environ['OPENBLAS_NUM_THREADS'] == '1'\n"
        "from inertia_kit.physics.primitives import box\n"
        "box((1, 1, 1), mass=1)\n"
        "heavy = {'trimesh', 'manifold3d', 'lxml', 'xacro'} & set(sys.modules)\n"
        "assert not heavy, heavy\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_user_choice_of_blas_threads_is_kept():
    code = (
        "import os; os.environ['OPENBLAS_NUM_THREADS'] = '2'\n"
        "import inertia_kit.cli\n"
        "assert os.environ['OPENBLAS_NUM_THREADS'] == '2'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)


def test_all_lists_exactly_the_lazy_exports():
    assert set(inertia_kit.__all__) == {*inertia_kit._EXPORTS, "__version__"}
