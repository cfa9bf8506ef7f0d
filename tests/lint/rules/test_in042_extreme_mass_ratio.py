"""IN042 extreme-mass-ratio: the two sides of a moving joint differ hugely in mass."""

from __future__ import annotations

from kit.urdf import inertial, joint, link, robot

from inertia_kit.lint.findings import Severity


def chain(body: float, tip: float, kind: str = "continuous", welded: float | None = None) -> str:
    """base → (yaw) → `body` [welded to `plate`] → (``kind`` `tip_joint`) → `tip`, by mass."""
    weld = (
        ()
        if welded is None
        else (joint("body", "plate", "fixed", name="w"), link("plate", inertial(welded, 1e-4)))
    )
    return robot(
        link("base"),
        joint("base", "body", "continuous", name="yaw"),
        link("body", inertial(body, 1e-4)),
        *weld,
        joint("body", "tip", kind, name="tip_joint"),
        link("tip", inertial(tip, 1e-4)),
    )


def test_ratio_beyond_default_warns(lint):
    findings = lint(chain(20.0, 0.005), "IN042")
    assert len(findings) == 1
    finding = findings[0]
    assert finding.severity == Severity.WARNING
    assert finding.joint == "tip_joint" and finding.link == "tip"
    assert "`tip` weighs 0.005 kg, 1/4000 of `body` at 20 kg (beyond 1/1000)" in finding.message
    assert finding.expected["ratio"] == 4000.0


def test_ratio_within_default_is_quiet(lint):
    assert lint(chain(20.0, 0.05), "IN042") == []


def test_fixed_joint_is_not_compared(lint):
    assert lint(chain(20.0, 0.001, kind="fixed"), "IN042") == []


def test_welded_links_count_as_one_body(lint):
    # 0.5 + 19.5 kg welded: the tip compares with 20 kg
    findings = lint(chain(0.5, 0.005, welded=19.5), "IN042")
    assert len(findings) == 1
    assert "`body` (with 1 welded link) at 20 kg" in findings[0].message


def test_massless_side_is_skipped(lint):
    # the yaw joint joins a massless base to the body: IN001's business, not a ratio
    assert lint(chain(2000.0, 1000.0), "IN042") == []


def test_heavier_child_is_reported_too(lint):
    findings = lint(chain(0.01, 20.0), "IN042")
    assert len(findings) == 1 and "`body` weighs 0.01 kg" in findings[0].message


def test_max_ratio_option(lint):
    assert lint(chain(20.0, 0.05), "IN042", options={"IN042": {"max_ratio": 100.0}}) != []
    assert lint(chain(20.0, 0.005), "IN042", options={"IN042": {"max_ratio": 1e4}}) == []
