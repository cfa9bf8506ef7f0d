"""IN071 gazebo-verdict: edge cases beyond the document's examples."""

from __future__ import annotations

from kit.urdf import LIMIT, inertial, link, robot

BOX = inertial(1, 0.01)


def run(lint, body):
    return lint(robot(body), select="IN071", engines=("gazebo",))


def test_loads_unchanged_gives_nothing(lint):
    assert run(lint, link("a", BOX)) == []


def test_runs_only_with_its_engine(lint):
    text = robot(link("a"))
    assert lint(text, select="IN071") == []


def test_massless_moving_link_dropped_with_subtree(lint):
    found = run(
        lint,
        f"""<link name="a">{BOX}</link>
        <joint name="j" type="revolute"><parent link="a"/><child link="b"/>{LIMIT}</joint>
        <link name="b"><inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0"
          iyz="0" izz="0"/></inertial></link>
        <joint name="k" type="revolute"><parent link="b"/><child link="c"/>{LIMIT}</joint>
        <link name="c">{BOX}</link>""",
    )
    assert [(f.link, f.joint) for f in found] == [("b", "j"), ("c", "k")]
    first = found[0]
    assert (
        first.message
        == "link `b`: Gazebo drops it with its joint and the 1 link below it: mass 0 kg"
    )
    for words in (
        "has a mass value of less than or equal to zero",
        "urdf2sdf: parent joint[j] ignored.",
        "urdf2sdf: link[b] is not modeled in sdf.",
    ):
        assert words in first.detail and words in first.expected["engine_message"]
    assert "with its joint `j` and the 1 link below it (`c`)" in first.detail
    assert first.expected["verdict"] == "changes" and first.severity.name == "WARNING"
    assert found[1].message == "link `c`: Gazebo drops it with its joint: an ancestor has no mass"
    assert "ancestor `b`" in found[1].detail


def test_massless_frame_on_fixed_joint_is_lumped(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="f" type="fixed"><parent link="a"/><child link="tool0"/></joint>
      <link name="tool0"/>"""
    assert run(lint, body) == []


def test_preserved_massless_fixed_link_is_dropped(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="f" type="fixed"><parent link="a"/><child link="tool0"/></joint>
      <link name="tool0"/>
      <gazebo reference="f"><preserveFixedJoint>true</preserveFixedJoint></gazebo>"""
    (finding,) = run(lint, body)
    assert finding.link == "tool0" and "allowing joint lumping by removing" in finding.detail


def test_tiny_mass_dropped_by_old_sdformat(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b"><inertial><mass value="1e-7"/><inertia ixx="1e-9" ixy="0" ixz="0"
        iyy="1e-9" iyz="0" izz="1e-9"/></inertial></link>"""
    (finding,) = run(lint, body)
    assert finding.message == "link `b`: older Gazebo drops it: mass 1e-07 kg, below 1e-06 kg"
    assert "has no inertia, not modeled in sdf" in finding.detail
    assert "before 9.10.1 / 14.1.0" in finding.detail


def test_invalid_lumped_inertia_is_refused(lint):
    body = """<link name="a"><inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0"
      iyy="0.01" iyz="0" izz="0.05"/></inertial></link>"""
    (finding,) = run(lint, body)
    assert finding.severity.name == "ERROR"
    assert finding.expected["engine_message"] == "A link named a has invalid inertia."
    assert (
        finding.message == "link `a`: Gazebo rejects its inertia: principal moments break A + B ≥ C"
    )
    assert "principal moments (0.01, 0.01, 0.05) kg·m²" in finding.detail


def test_message_is_one_short_line_and_the_detail_quotes_gazebo(lint):
    body = f"""<link name="a">{BOX}</link>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/>{LIMIT}</joint>
      <link name="b"/>"""
    (finding,) = run(lint, body)
    assert finding.message == "link `b`: Gazebo drops it with its joint: no <inertial>"
    assert len(finding.message) <= 100
    assert "urdf2sdf" not in finding.message
    assert finding.detail.startswith(
        "sdformat's URDF converter does not model link `b` (no <inertial>): it drops it with its "
        "joint `j`."
    )
    assert finding.detail.endswith(f'Gazebo says: "{finding.expected["engine_message"]}"')
