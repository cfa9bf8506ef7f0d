"""
Xacro files whose expansion runs away (issue 11's reproducers), for the tests of the xacro limits.

- ``expression_robot(expr)``: a robot whose one link is named ``a${expr}`` (line 3).
- ``doubling_chain(levels)``: macro ``m0`` makes a link, ``mK`` calls ``m(K-1)`` twice, and
  ``m<levels>`` is called once: 2**levels links.
"""

from __future__ import annotations

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'

#: ``${'x'*10**10}``: a 10 GB string
HUGE_STRING = "'x'*10**10"
#: ``${10**10**10}``: an integer of 10**10 digits, one C call that no signal interrupts
HUGE_POWER = "10**10**10"
#: levels of the doubling chain: 2**22 links
CHAIN_LEVELS = 22
#: the line of ``expression_robot``'s link
EXPRESSION_LINE = 3


def expression_robot(expr: str) -> str:
    link = f'<link name="a${{{expr}}}"/>'
    return f'<?xml version="1.0"?>\n<robot name="r" {NS}>\n  {link}\n</robot>\n'


def doubling_chain(levels: int = CHAIN_LEVELS) -> str:
    lines = [
        '<?xml version="1.0"?>',
        f'<robot name="r" {NS}>',
        '  <xacro:macro name="m0"><link name="l"/></xacro:macro>',
        *(
            f'  <xacro:macro name="m{k}"><xacro:m{k - 1}/><xacro:m{k - 1}/></xacro:macro>'
            for k in range(1, levels + 1)
        ),
        f"  <xacro:m{levels}/>",
        "</robot>",
    ]
    return "\n".join(lines) + "\n"
