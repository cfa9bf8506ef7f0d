"""analysis.geometry: each shape evaluated as a solid, placed by its origin."""

from __future__ import annotations


def test_solids_lie_where_their_origins_place_them(analysed):
    """Points just inside and just outside each placed primitive, seen through its hull."""
    analysis = analysed(
        """<link name="a">
          <collision><geometry><box size="0.2 0.2 0.2"/></geometry></collision>
          <collision><origin xyz="1 0 0" rpy="0 1.5707963 0"/>
            <geometry><cylinder radius="0.1" length="0.4"/></geometry></collision>
          <collision><origin xyz="0 1 0"/><geometry><sphere radius="0.1"/></geometry></collision>
          <collision><origin xyz="0 0 1"/>
            <geometry><capsule radius="0.1" length="0.2"/></geometry></collision>
        </link>""",
    )
    box, cylinder, sphere, capsule = analysis.links[0].collision.solids

    def inside(solid, point):
        return solid.hull.distance_outside(point) == 0.0

    assert inside(box, (0.09, -0.09, 0.09)) and not inside(box, (0.11, 0, 0))
    assert inside(cylinder, (1.19, 0.0, 0.0)) and not inside(cylinder, (1.0, 0.0, 0.11))
    assert inside(sphere, (0.0, 1.0, 0.099)) and not inside(sphere, (0.08, 1.08, 0.0))
    assert inside(capsule, (0.0, 0.0, 1.19)) and not inside(capsule, (0.09, 0.0, 1.19))
    assert box.hull.distance_outside((0.105, 0, 0)) <= 0.01
