"""inertia-kit: physically right mass properties for URDF and xacro robot descriptions."""

from inertia_kit.mass import MassProperties, Validity
from inertia_kit.primitives import box, capsule, cylinder, ellipsoid, sphere

__all__ = ["MassProperties", "Validity", "box", "capsule", "cylinder", "ellipsoid", "sphere"]
__version__ = "0.1.0"
