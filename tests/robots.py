"""Robot texts the tests build on (the shell around the link a test is about)."""

from __future__ import annotations

SHELL = """<robot name="r">
  <link name="base"/>
  <joint name="j" type="revolute">
    <parent link="base"/><child link="{name}"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/>
  </joint>
  <link name="{name}">{body}</link>
</robot>"""


def moving(body: str, name: str = "plate") -> str:
    """A robot whose one moving link ``name`` (revolute on a massless base) holds ``body``."""
    return SHELL.format(name=name, body=body)
