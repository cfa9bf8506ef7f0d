"""
Mass properties as a description file holds them, whatever its format: how many digits are
written (:data:`DIGITS`), which products of inertia are rounding noise (:data:`PRODUCT_FLOOR`),
what the next run reads back (:func:`as_written`: what makes a fill a fixed point), what cannot
be written (:func:`unwritable`), and the ``<inertial>`` element in each format's words
(:func:`inertial_text`: URDF's block, :mod:`.urdf.inertial_xml`; MJCF's element,
:mod:`.mjcf.writer`). A third format's writer is a third branch here.
"""

from __future__ import annotations

from inertia_kit.physics.formatting import xml_number
from inertia_kit.physics.mass import MassProperties

# significant digits written: CAD tools report about six; more only adds churn
DIGITS = 6


# products of inertia below this share of the largest moment are under half the last digit
# written of that moment: rounding noise of a rotation (rpy="1.5708 0 0") written as zero
PRODUCT_FLOOR = 5e-6


def mass_text(mass: float) -> str:
    """A mass as every format writes it."""
    return xml_number(mass, DIGITS)


def as_written(properties: MassProperties, digits: int = DIGITS) -> MassProperties:
    """
    ``properties`` as a file holds them once written, and as the next run reads them back: the
    mass as its text reads, the tensor scaled to that mass (what the next run computes from it),
    the centre of mass as its text reads. Writing these instead of the values computed is what
    makes filling a fixed point: a second run computes the same tensor and writes no new digit.
    """
    mass = float(xml_number(properties.mass, digits))
    scaled = properties.with_mass(mass) if properties.mass > 0 and mass > 0 else properties
    com = [float(xml_number(x, digits)) for x in properties.cleaned().com]
    return MassProperties(mass, com, scaled.inertia)


def unwritable(properties: MassProperties) -> str | None:
    """
    Why ``properties`` must not be written: a value not finite, or one the linter refuses as
    written (IN004: beyond ±1e50, subnormal, a mass or moment below 1e-50), or no positive
    mass; ``None`` when they can be.
    """
    from inertia_kit.description.urdf.inertial_xml import unwritable as refused

    return refused(properties)


def values_text(properties: MassProperties) -> dict[str, str]:
    """The values as written, by name: ``xyz``, ``mass`` and the six tensor entries in the
    body's axes (``ixx`` … ``izz``), for messages."""
    from inertia_kit.description.urdf.inertial_xml import inertial_values

    return inertial_values(properties)


def inertial_text(
    properties: MassProperties, form: str = "urdf", *, indent: str = "  ", level: int = 0
) -> str:
    """The ``<inertial>`` element for ``properties`` (body frame, about the centre of mass) in
    the words of the format ``form`` (``urdf``, ``mjcf``), without a trailing newline."""
    if form == "mjcf":
        from inertia_kit.description.mjcf.writer import inertial_element

        return indent * level + inertial_element(properties)
    from inertia_kit.description.urdf.inertial_xml import inertial_block

    return inertial_block(properties, indent=indent, level=level)
