"""
IN070's mesh inertia against the real MuJoCo: a link without ``<inertial>`` gets its collision
meshes' mass properties by MuJoCo's default mesh inertia, ``legacy``, which overcounts a
non-convex mesh's volume; an MJCF that asks for ``exact`` gets the exact integrals.
"""

from __future__ import annotations

import numpy as np
import pytest
import trimesh
from kit.meshes import binary_stl, box_triangles
from kit.urdf import collision, joint, link, mesh, robot

from inertia_kit.engines.mujoco_meshes import DEFAULT_MESH_INERTIA
from inertia_kit.lint.runner import Selection, lint_file
from inertia_kit.physics.meshes import mesh as exact_mesh
from inertia_kit.physics.mujoco_mesh_inertia import soup_mass_properties as mode_unit

mujoco = pytest.importorskip("mujoco")


@pytest.fixture(autouse=True)
def _in_tmp_path(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # MuJoCo writes MUJOCO_LOG.TXT in the cwd


def _l_shape() -> np.ndarray:
    """Two 0.1 m square bars, 0.3 m long, crossing at one end: an L of 0.005 m³ (non-convex)."""
    a = trimesh.creation.box(extents=(0.3, 0.1, 0.1))
    a.apply_translation((0.15, 0.05, 0.05))
    b = trimesh.creation.box(extents=(0.1, 0.3, 0.1))
    b.apply_translation((0.05, 0.15, 0.05))
    return np.asarray(a.union(b).triangles)


def _urdf(tmp_path, name, extension=""):
    text = robot(
        link("base"),
        joint("base", "arm"),
        link("arm", collision(mesh(name), xyz="0.01 0.02 0.03", rpy="0.1 0.2 0.3")),
    )
    path = tmp_path / "robot.urdf"
    path.write_text(text.replace("</robot>", extension + "</robot>"))
    return path


def _body(loaded, index=1):
    return float(loaded.body_mass[index]), np.sort(loaded.body_inertia[index])


def _principal(value):
    return np.sort(np.linalg.eigvalsh(np.asarray(value.inertia)))


def test_default_mode_is_legacy():
    assert mujoco.MjSpec().add_mesh().inertia == mujoco.mjtMeshInertia.mjMESH_INERTIA_LEGACY
    assert DEFAULT_MESH_INERTIA == "legacy"


@pytest.mark.parametrize("mode", ["legacy", "exact"])
def test_mjcf_modes_match_legacy_and_exact(tmp_path, mode):
    (tmp_path / "l.stl").write_bytes(binary_stl(_l_shape()))
    xml = f"""<mujoco><asset><mesh name="l" file="l.stl" inertia="{mode}"/></asset>
      <worldbody><body><freejoint/><geom type="mesh" mesh="l" density="1"/></body></worldbody>
      </mujoco>"""
    (tmp_path / "l.xml").write_text(xml)
    mass, moments = _body(mujoco.MjModel.from_xml_path(str(tmp_path / "l.xml")))
    if mode == "legacy":
        ours = mode_unit(_l_shape(), "legacy")
    else:
        ours = exact_mesh(tmp_path / "l.stl", density=1.0).mass_properties
        assert ours.mass == pytest.approx(0.005, rel=1e-6)  # the L's own volume
    assert ours is not None
    assert mass == pytest.approx(ours.mass, rel=1e-9)
    assert moments == pytest.approx(_principal(ours), rel=1e-9)


def test_legacy_overcounts_a_non_convex_mesh_and_not_a_convex_one():
    legacy = mode_unit(_l_shape(), "legacy")
    assert legacy is not None and legacy.mass > 0.005 * 1.05  # +6 %
    cube = mode_unit(box_triangles((0.1, 0.2, 0.3), low=(0.4, -0.1, 0.0)), "legacy")
    assert cube is not None
    # MuJoCo holds a file's vertices as float32: 0.4 is 0.4000000059604645
    assert cube.mass == pytest.approx(0.006, rel=1e-7)
    assert np.asarray(cube.com) == pytest.approx([0.45, 0.0, 0.15])
    expected = 0.006 / 12 * np.array([0.2**2 + 0.3**2, 0.1**2 + 0.3**2, 0.1**2 + 0.2**2])
    assert np.diag(cube.inertia) == pytest.approx(expected, rel=1e-6)


@pytest.mark.parametrize(
    "extension",
    [
        "",
        # read (boundmass takes effect, see below), but no attribute selects the mesh inertia
        '<mujoco><compiler exactmeshinertia="true"/></mujoco>',
        '<mujoco><default><mesh inertia="exact"/></default></mujoco>',
    ],
)
def test_urdf_link_without_inertial_gets_the_legacy_body(tmp_path, extension):
    (tmp_path / "l.stl").write_bytes(binary_stl(_l_shape()))
    path = _urdf(tmp_path, "l.stl", extension)
    mass, moments = _body(mujoco.MjModel.from_xml_path(str(path)))
    result = lint_file(path, Selection(select=(), engines=("mujoco",)))
    (finding,) = [f for f in result.findings if f.expected.get("stage") == "inertiafromgeom"]
    assert finding.expected["mesh_inertia"] == "legacy"
    assert "default mesh inertia `legacy`" in finding.detail
    assert finding.expected["mass"] == pytest.approx(mass, rel=1e-9)
    assert finding.expected["principal_moments"] == pytest.approx(moments, rel=1e-9)
    assert mass > 1000 * 0.005 * 1.05  # not the exact 5 kg


def test_the_urdf_compiler_extension_is_read(tmp_path):
    """The extension element is honoured (so its silence on mesh inertia is MuJoCo's)."""
    (tmp_path / "l.stl").write_bytes(binary_stl(_l_shape()))
    path = _urdf(tmp_path, "l.stl", '<mujoco><compiler boundmass="100"/></mujoco>')
    assert _body(mujoco.MjModel.from_xml_path(str(path)))[0] == 100.0


def test_primitives_only_quote_no_mesh_mode(tmp_path):
    from kit.urdf import box

    path = tmp_path / "robot.urdf"
    path.write_text(robot(link("base"), joint("base", "arm"), link("arm", collision(box(1, 1, 1)))))
    result = lint_file(path, Selection(select=(), engines=("mujoco",)))
    (finding,) = [f for f in result.findings if f.expected.get("stage") == "inertiafromgeom"]
    assert finding.expected["mesh_inertia"] is None and "mesh inertia" not in finding.detail
