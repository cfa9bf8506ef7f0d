"""
YAML read through ``xacro.load_yaml``, bounded as the rest of an expansion: an alias bomb (7-12 s
and 710 MB before it was refused at the memory limit) is refused at once, naming the YAML file
and the xacro line; an alias inside its own anchor, nesting PyYAML cannot read, a file that is
not a regular file or is over the bound are refused naming it; what xacro gave a real YAML
file (dotted access, units) it still gives, and xacro is left as it was.
"""

from __future__ import annotations

import math
import os
import resource
import time

import pytest
from kit import write
from kit.runaway_xacro import NS

from inertia_kit.description import safexml
from inertia_kit.description.loader import load
from inertia_kit.description.urdf import xacro_sandbox
from inertia_kit.description.urdf.xacro_yaml import expanded_size
from inertia_kit.errors import InputError


@pytest.fixture(params=["child", "in-process"])
def mode(request, monkeypatch) -> str:
    if request.param == "in-process":
        monkeypatch.setattr(xacro_sandbox, "can_fork", lambda: False)
    elif not xacro_sandbox.can_fork():
        pytest.skip("no os.fork here")
    return request.param


def reading(folder, yaml_text: str | None, expression: str = "str(y)[:5]"):
    """``robot.xacro`` loading ``data.yaml`` (written unless None) into ``y`` on line 2, and a
    link named by ``expression`` on line 3."""
    if yaml_text is not None:
        write(folder / "data.yaml", yaml_text)
    return write(
        folder / "robot.xacro",
        f'<robot name="r" {NS}>\n'
        '  <xacro:property name="y" value="${xacro.load_yaml(\'data.yaml\')}"/>\n'
        f'  <link name="l${{{expression}}}"/>\n'
        "</robot>\n",
    )


def bomb(levels: int = 9, width: int = 9) -> str:
    lines = ["a0: &a0 [" + ", ".join(['"xxxxxxxxxx"'] * width) + "]"]
    for level in range(1, levels):
        lines.append(f"a{level}: &a{level} [" + ", ".join([f"*a{level - 1}"] * width) + "]")
    return "\n".join(lines) + "\n"


def test_an_alias_bomb_is_refused_at_once(tmp_path, mode):
    robot = reading(tmp_path, bomb())
    began = time.monotonic()
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    with pytest.raises(InputError) as caught:
        load(robot)
    assert time.monotonic() - began < 3
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss - peak < 100_000  # kB
    error = caught.value
    assert (error.path, error.line) == (str(robot), 3)
    # the root mapping, its 9 keys, and a0 ... a8: a0 = 10 nodes, a(k) = 1 + 9 a(k-1)
    assert "the YAML file data.yaml holds 490329064 nodes once its aliases are expanded" in (
        error.message
    )
    assert "--xacro-limit elements=COUNT" in error.message


def test_an_alias_inside_its_own_anchor_is_refused(tmp_path, mode):
    with pytest.raises(InputError, match=r"data\.yaml holds an alias inside its own anchor"):
        load(reading(tmp_path, "a: &a [1, *a]\n"))


def test_nesting_pyyaml_cannot_read_is_refused(tmp_path, mode):
    depth = 5000
    with pytest.raises(InputError, match=r"data\.yaml is nested deeper than PyYAML can read"):
        load(reading(tmp_path, "a: " + "[" * depth + "]" * depth + "\n"))


@pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="no named pipes here")
def test_a_yaml_file_that_is_not_a_regular_file_is_refused(tmp_path, mode):
    robot = reading(tmp_path, None)
    os.mkfifo(tmp_path / "data.yaml")
    with pytest.raises(InputError, match=r"data\.yaml: is a named pipe, not a regular file"):
        load(robot)


def test_a_yaml_file_over_the_bound_is_refused(tmp_path, mode, monkeypatch):
    robot = reading(tmp_path, "a: " + "x" * 500 + "\n")
    monkeypatch.setattr(safexml, "MAX_BYTES", 400)
    with pytest.raises(InputError, match=r"data\.yaml: is larger than 400 bytes; no YAML file"):
        load(robot)


def test_a_real_yaml_file_reads_as_xacro_reads_it(tmp_path, mode):
    import xacro

    def symbols():  # eval adds __builtins__ to the globals it is given: xacro's, not ours
        found = {k: v for k, v in xacro._global_symbols.items() if k != "__builtins__"}
        return xacro.load_yaml, found, dict(xacro._global_symbols["xacro"])

    before = symbols()
    text = "arm:\n  length: 0.5\n  angle: !degrees 90\nlist: [1, 2, 3]\nshared: &s {a: 1}\nb: *s\n"
    robot = reading(tmp_path, text, "y.arm.length + y['list'][2] + y.arm.angle + y.b.a")
    (link,) = load(robot).links
    assert float(link.name[1:]) == pytest.approx(0.5 + 3 + math.pi / 2 + 1)
    assert symbols() == before


def test_the_bare_load_yaml_is_bounded_too(tmp_path, mode):
    write(tmp_path / "data.yaml", bomb())
    robot = write(
        tmp_path / "robot.xacro",
        f'<robot name="r" {NS}>\n  <link name="l${{str(load_yaml(\'data.yaml\'))[:3]}}"/>\n'
        "</robot>\n",
    )
    with pytest.raises(InputError, match="nodes once its aliases are expanded"):
        load(robot)


def test_expanded_size_counts_each_alias_as_what_it_stands_for():
    import yaml

    def size(text):
        return expanded_size(yaml.compose(text, Loader=yaml.SafeLoader))

    assert size("[1, 2]") == 3
    assert size("{a: 1}") == 3
    assert size("a: &x [1, 2]\nb: [*x, *x]") == 1 + 2 + 3 + (1 + 2 * 3)
    assert size(bomb(3, 4)) == 1 + 3 * 2 + (1 + 4) + (1 + 4 * 5) + (1 + 4 * 21) - 3
    assert size("a: &a [*a]") is None
