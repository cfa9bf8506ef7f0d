"""IN074 kdl-verdict: edge cases beyond the document's examples."""

from __future__ import annotations

from kit.urdf import inertial, link, robot

BOX = inertial(1, 0.01)


def run(lint, body):
    return lint(robot(body), select="IN074", engines=("kdl",))


def test_massless_root_gives_nothing(lint):
    body = f"""<link name="root"/>
      <joint name="f" type="fixed"><parent link="root"/><child link="a"/></joint>
      <link name="a">{BOX}</link>"""
    assert run(lint, body) == []


def test_root_inertia_ignored_with_kdl_message(lint):
    (finding,) = run(lint, link("a", BOX))
    assert finding.expected["engine_message"].startswith(
        "The root link a has an inertia specified in the URDF, but KDL does not support"
    )
    assert finding.message == "link `a`: KDL ignores the root link's inertia (1 kg)"
    assert len(finding.message) <= 100
    assert "the root link `a` (1 kg)" in finding.detail
    assert finding.detail.endswith(f'KDL says: "{finding.expected["engine_message"]}"')


def test_floating_joint_becomes_fixed(lint):
    body = f"""<link name="root"/>
      <joint name="free" type="floating"><parent link="root"/><child link="a"/></joint>
      <link name="a">{BOX}</link>"""
    (finding,) = run(lint, body)
    assert finding.joint == "free"
    assert finding.message == "link `a`: KDL makes its floating joint fixed"
    assert "the floating joint `free` becomes fixed, welding link `a` to `root`" in finding.detail
    assert "Converting unknown joint type of joint 'free' into a fixed joint" in finding.detail
