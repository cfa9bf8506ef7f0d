"""analysis.expected: the geometry's tensor in the axes a link's <inertia> is written in."""

from __future__ import annotations

import numpy as np
import pytest

from inertia_kit.analysis.expected import basis_text, geometry_tensor, tensor_fields

BOX = '<collision><geometry><box size="0.4 0.2 0.1"/></geometry></collision>'


def box_moments(mass, x, y, z):
    return np.array([y * y + z * z, x * x + z * z, x * x + y * y]) * mass / 12


def test_in_the_link_axes(analysed):
    link = analysed(f'<link name="a">{BOX}</link>').links[0]
    written = geometry_tensor(link, 2.0)
    assert written is not None and written.axes == ""
    np.testing.assert_allclose(np.diag(written.tensor), box_moments(2.0, 0.4, 0.2, 0.1))
    assert written.fields == tensor_fields(written.tensor)
    assert list(written.fields) == ["ixx", "ixy", "ixz", "iyy", "iyz", "izz"]
    assert written.text() == "ixx = 0.008333, iyy = 0.02833, izz = 0.03333 kg·m²"
    assert written.text(["izz"]) == "izz = 0.03333 kg·m²"
    assert basis_text(link, 2.0) == (
        "its collision box (0.4 × 0.2 × 0.1 m) with the declared 2 kg gives"
    )


def test_in_the_axes_of_a_rotated_inertial(analysed):
    """With <inertial><origin rpy="0 0 π/2">, x and y swap: the values to write say so."""
    link = analysed(
        f"""<link name="a">{BOX}<inertial><origin rpy="0 0 1.5707963267948966"/>
        <mass value="2"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>
        </inertial></link>"""
    ).links[0]
    written = geometry_tensor(link, 2.0)
    assert written is not None
    x, y, z = box_moments(2.0, 0.4, 0.2, 0.1)
    assert written.fields["ixx"] == pytest.approx(y) and written.fields["iyy"] == pytest.approx(x)
    assert written.fields["izz"] == pytest.approx(z)
    assert written.text().endswith("kg·m² in the axes of its `<inertial><origin rpy>`")


def test_no_tensor_without_a_volume(analysed):
    link = analysed('<link name="a"/>').links[0]
    assert geometry_tensor(link, 2.0) is None
