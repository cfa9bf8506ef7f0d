"""IN040 broken-tree: names, joint ends and types, parents, roots and cycles."""

from __future__ import annotations

import pytest
from kit.urdf import joint, link, robot

from inertia_kit.lint.findings import Severity


def test_a_tree_is_quiet(lint):
    text = robot(
        link("a"), link("b"), link("c"), joint("a", "b", name="ab"), joint("b", "c", name="bc")
    )
    assert lint(text, "IN040") == []


def test_single_link_is_quiet(lint):
    assert lint(robot(link("a")), "IN040") == []


def test_unknown_child_with_suggestion_and_second_root(lint):
    findings = lint(robot(link("base"), link("arm"), joint("base", "amr", name="j")), "IN040")
    messages = [f.message for f in findings]
    assert any(
        "child link `amr`, which does not exist (did you mean `arm`?)" in m for m in messages
    )
    assert any("link `arm` is a second root" in m and "`base`" in m for m in messages)
    assert all(f.severity == Severity.ERROR for f in findings)
    assert {f.joint for f in findings} == {"j", None}


def test_duplicate_names(lint):
    text = robot(
        link("a"),
        link("b"),
        link("b"),
        joint("a", "b", name="j"),
        joint("a", "b", "fixed", name="j"),
    )
    messages = [f.message for f in lint(text, "IN040")]
    assert any("link `b` is defined twice (first at line 1)" in m for m in messages)
    assert any("joint `j` is defined twice" in m for m in messages)


def test_unnamed_link_and_joint(lint):
    text = robot(link("a"), "<link/>", '<joint type="fixed"><parent link="a"/></joint>')
    messages = [f.message for f in lint(text, "IN040")]
    assert "a <link> has no name: urdfdom refuses the file" in messages
    assert "a <joint> has no name: urdfdom refuses the file" in messages
    assert "a joint has no <child link>: urdfdom refuses the file" in messages


def test_missing_parent_element(lint):
    text = robot(link("a"), link("b"), '<joint name="j" type="fixed"><child link="b"/></joint>')
    messages = [f.message for f in lint(text, "IN040")]
    assert "joint `j` has no <parent link>: urdfdom refuses the file" in messages


def test_joint_to_itself(lint):
    findings = lint(robot(link("a"), joint("a", "a", "fixed", name="j")), "IN040")
    messages = [f.message for f in findings]
    assert "joint `j` joins link `a` to itself" in messages
    # urdfdom's view as well: `a` is a child, so there is no root
    assert any(m.startswith("no root link") for m in messages)


def test_link_with_two_parents(lint):
    text = robot(
        link("a"), link("b"), link("c"), joint("a", "b", name="ab"), joint("a", "c", name="ac"),
        joint("c", "b", name="cb"),
    )  # fmt: skip
    findings = lint(text, "IN040")
    assert len(findings) == 1
    assert "link `b` has two parent joints: `ab` (line 1) and `cb`" in findings[0].message
    assert findings[0].joint == "cb" and findings[0].link == "b"


def test_several_roots_name_the_largest_tree(lint):
    text = robot(
        link("lonely"), link("a"), link("b"), link("c"), link("d"), link("e"),
        joint("a", "b", name="ab"), joint("b", "c", name="bc"), joint("d", "e", name="de"),
    )  # fmt: skip
    findings = lint(text, "IN040")
    messages = sorted(f.message for f in findings)
    assert len(messages) == 2
    assert "link `d` is a second root (a subtree of 2 links" in messages[0]
    assert "tree of `a`" in messages[0]
    assert "link `lonely` is a second root (a link no joint connects" in messages[1]


def test_cycle(lint):
    text = robot(
        link("root"), link("a"), link("b"), link("c"),
        joint("root", "a", name="ra"), joint("a", "b", name="ab"), joint("b", "c", name="bc"),
        joint("c", "a", name="ca"),
    )  # fmt: skip
    messages = [f.message for f in lint(text, "IN040")]
    assert any("link `a` has two parent joints" in m for m in messages)
    text = robot(
        link("root"), link("a"), link("b"), joint("a", "b", name="ab"), joint("b", "a", name="ba"),
    )  # fmt: skip
    messages = [f.message for f in lint(text, "IN040")]
    assert any("form a cycle" in m and "`ab`" in m and "`ba`" in m for m in messages)


def test_everything_in_a_cycle_has_no_root(lint):
    text = robot(link("a"), link("b"), joint("a", "b", name="ab"), joint("b", "a", name="ba"))
    findings = lint(text, "IN040")
    assert any(f.message.startswith("no root link") for f in findings)
    cycle = next(f for f in findings if f.message.startswith("joints"))
    assert cycle.message in (
        "joints `ab` and `ba` form a cycle",
        "joints `ba` and `ab` form a cycle",
    )
    assert "`a` → `b` → `a`" in cycle.detail or "`b` → `a` → `b`" in cycle.detail


@pytest.mark.parametrize(
    ("kind", "expected"),
    [
        ("revolut", "unknown type `revolut` (did you mean `revolute`?)"),
        ("spherical", "type `spherical` (PyBullet's ball joint, no URDF type)"),
        ("", "has no type"),
    ],
)
def test_joint_types(lint, kind, expected):
    text = robot(
        link("a"), link("b"), f'<joint name="j" type="{kind}"><parent link="a"/>'
        '<child link="b"/></joint>',
    )  # fmt: skip
    findings = lint(text, "IN040")
    assert len(findings) == 1 and expected in findings[0].message


def test_extra_joint_types_option(lint):
    text = robot(
        link("a"), link("b"), '<joint name="j" type="spherical"><parent link="a"/>'
        '<child link="b"/></joint>',
    )  # fmt: skip
    assert lint(text, "IN040", options={"IN040": {"extra_joint_types": ("spherical",)}}) == []


def test_no_links(lint):
    findings = lint('<robot name="r"></robot>', "IN040")
    assert len(findings) == 1 and "has no <link>" in findings[0].message
    assert "No link elements found in urdf file" in findings[0].detail


def test_the_message_is_one_short_line_and_the_detail_has_the_basis(lint):
    chain = [link(name) for name in "abcde"]
    chain += [joint(a, b, name=a + b) for a, b in zip("abcde", "bcdea", strict=True)]
    findings = lint(robot(link("root"), *chain), "IN040")
    (cycle,) = [f for f in findings if f.message.startswith("joints")]
    assert cycle.message == "joints `ea`, `de`, `cd` and 2 more form a cycle"
    assert cycle.detail == "the cycle: `b` → `c` → `d` → `e` → `a` → `b`"
    text = robot(
        link("a"), link("b"), '<joint name="j" type="revolut"><parent link="a"/>'
        '<child link="b"/></joint>',
    )  # fmt: skip
    (finding,) = lint(text, "IN040")
    assert len(finding.message) <= 100
    assert finding.detail == (
        'urdfdom refuses the file ("Joint [j] has no known type [revolut]"), and with it ROS '
        "and Gazebo"
    )
