"""The fuzz harness's own parts: inputs are reproducible, the checks see what they look for."""

from __future__ import annotations

from fuzz.campaign import CI, generate
from fuzz.checks import _injected, check_tree
from fuzz.mutate import CANARY
from fuzz.plan import Invocation
from fuzz.shrink import shrink
from fuzz.tree import Seen, Tree, file


def test_an_input_is_the_same_for_the_same_seed_and_index():
    for index in range(30):
        first, second = generate("s", index, CI)[0], generate("s", index, CI)[0]
        assert first.to_json() == second.to_json()
    assert generate("s", 1, CI)[0].to_json() != generate("t", 1, CI)[0].to_json()


def test_an_injected_line_and_a_raw_control_character_are_seen():
    assert _injected(f"robot.urdf:3: link `a\n{CANARY}::error::x`", controls=True)
    assert _injected("name `a\x1b[31m`", controls=True) == "raw U+001B"
    assert _injected("name `a\u2028b`", controls=True) == "raw U+2028"
    assert _injected(f"name `a\\n{CANARY}` and\ttabs\n", controls=True) is None
    assert _injected("+ a diff line with\x0c", controls=False) is None


def test_writes_outside_the_repository_and_into_its_inputs_are_seen():
    lint = Invocation("inertia-lint", ("r.urdf",), ("lint",))
    fill = Invocation("inertia-fill", ("r.urdf",), ("fill",), writes=True)
    before = {
        "work/r.urdf": Seen("file", 0o644, "a", 1),
        "outside/deploy.sh": Seen("file", 0o755, "x", 1),
    }
    edited = {**before, "work/r.urdf": Seen("file", 0o644, "b", 2)}
    overwritten = {**before, "outside/deploy.sh": Seen("file", 0o755, "y", 9)}
    assert [f.kind for f in check_tree(lint, before, edited)[0]] == ["changed-input"]
    assert check_tree(fill, before, edited) == ([], ["work/r.urdf"])
    assert [f.kind for f in check_tree(fill, before, overwritten)[0]] == ["write-outside"]
    left = {**edited, "work/.r.urdf.inertia-kit-0123456789ab.tmp": Seen("file", 0o600, "c", 1)}
    assert [f.kind for f in check_tree(fill, before, left)[0]] == ["stray-file"]
    assert check_tree(fill, before, left, killed=True)[0] == []


def test_the_shrinker_keeps_what_still_fails():
    tree = Tree(main="r.urdf")
    lines = [f"<line{i}/>" for i in range(40)]
    tree.put("r.urdf", "\n".join(lines))
    tree.put("mesh.stl", b"solid")

    def fails(candidate: Tree) -> bool:
        return b"<line17/>" in candidate.get("r.urdf").data

    small, attempts = shrink(tree, fails, seconds=30, attempts=500)
    assert small.get("r.urdf").data.strip() == b"<line17/>"
    assert small.get("mesh.stl") is None and attempts < 500


def test_a_tree_survives_its_json():
    tree = Tree(main="a/r.urdf", env={"X": "1"}, notes=["n"])
    tree.put("a/r.urdf", file(b"\xff\x00bytes"))
    assert Tree.from_json(tree.to_json()).to_json() == tree.to_json()
