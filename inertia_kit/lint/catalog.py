"""
The rule catalogue: every rule module, imported by name (a missing one is an import error), and
all the linter asks of them: a rule by code or name, which rules a selector picks, and the
optional parts of the rule contract (options, engine, supersession), read here and nowhere else.
What a rule module holds is the contract in :mod:`inertia_kit.lint.rules`.

Adding a rule: write its module in ``rules/`` (the contract), import it below (that import list
is the registry), and write its document ``rules/<CODE>-<name>.md``. The rule documents are
found by :mod:`inertia_kit.lint.documents`, which imports no rule, so that ``--explain`` stays
fast.

A selector is what ``select``, ``ignore``, per-file ignores and suppression comments take: a
code (``IN012``), a code prefix (``IN01``, ``IN0``) or a rule name (``inertia-too-small``).
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from types import ModuleType
from typing import Any

from inertia_kit.lint.findings import Safety
from inertia_kit.lint.options import Option

# The registry: adding a rule is importing its module here. RULES below collects the modules this
# import binds, so nothing else names them (hence the noqa).
from inertia_kit.lint.rules import (  # noqa: F401
    in001_missing_inertial,
    in002_non_positive_mass,
    in003_incomplete_inertial,
    in004_invalid_number,
    in005_incomplete_geometry,
    in006_duplicated_element,
    in010_inertia_not_positive_definite,
    in011_inertia_triangle_inequality,
    in012_inertia_too_small,
    in013_placeholder_inertia,
    in020_inertia_geometry_mismatch,
    in021_com_geometry_mismatch,
    in022_implausible_density,
    in023_impossible_radius_of_gyration,
    in024_visual_collision_mismatch,
    in025_missing_collision,
    in026_degenerate_geometry,
    in030_mesh_not_found,
    in031_mesh_units,
    in032_mesh_not_watertight,
    in033_mesh_inverted,
    in034_mesh_unreadable,
    in040_broken_tree,
    in041_root_link_inertia,
    in042_extreme_mass_ratio,
    in050_joint_limits,
    in051_joint_axis,
    in060_inertia_about_other_point,
    in061_product_signs_flipped,
    in062_inertia_in_other_axes,
    in063_inertia_unit_slip,
    in064_inertia_attributes_transposed,
    in065_twin_links_disagree,
    in066_copied_inertial,
    in067_com_slip,
    in068_inertia_for_other_mass,
    in069_principal_axes_mismatch,
    in070_mujoco_verdict,
    in071_gazebo_verdict,
    in072_drake_verdict,
    in073_pybullet_verdict,
    in074_kdl_verdict,
    in090_unused_suppression,
)

_RULE_MODULES = "inertia_kit.lint.rules."

# Every rule module imported above, in code order. Read it as ``catalog.RULES``: tests put stub
# rules in its place.
RULES: tuple[ModuleType, ...] = tuple(
    sorted(
        (
            value
            for value in dict(globals()).values()
            if isinstance(value, ModuleType) and value.__name__.startswith(_RULE_MODULES)
        ),
        key=lambda rule: rule.CODE,
    )
)

CODE = re.compile(r"IN[0-9]{0,3}", re.IGNORECASE)  # a code or a code prefix, any case


def names() -> dict[str, str]:
    """``code -> name`` of every rule."""
    return {rule.CODE: rule.NAME for rule in RULES}


def find(key: str) -> ModuleType | None:
    """The rule with code ``key`` (any case) or name ``key``; ``None`` when there is none."""
    if CODE.fullmatch(key):
        return {rule.CODE: rule for rule in RULES}.get(key.upper())
    return {rule.NAME: rule for rule in RULES}.get(key)


# --- the optional parts of the contract ------------------------------------------------------


def options(rule: ModuleType) -> tuple[Option, ...]:
    """The options a rule declares (``OPTIONS``; none when it declares none)."""
    return tuple(getattr(rule, "OPTIONS", ()))


def option_values(rule: ModuleType, configured: Mapping[str, Any]) -> dict[str, Any]:
    """Every option of ``rule``: the configured value, else the declared default."""
    return {option.name: configured.get(option.name, option.default) for option in options(rule)}


#: the formats a rule judges when it does not say (``DESCRIPTION_FORMATS``)
ALL_FORMATS = ("urdf", "mjcf")


def formats(rule: ModuleType) -> tuple[str, ...]:
    """
    The description formats a rule judges (``DESCRIPTION_FORMATS``; every one when it does
    not say): a rule about what only URDF says or only URDF's readers do (``<limit>``, KDL's
    root, a second ``<inertial>``) stays silent on an MJCF model.
    """
    return tuple(getattr(rule, "DESCRIPTION_FORMATS", ALL_FORMATS))


def engine(rule: ModuleType) -> str | None:
    """The engine an engine rule (IN07x) speaks for (``ENGINE``); ``None`` for other rules."""
    return getattr(rule, "ENGINE", None)


def fix_safety(rule: ModuleType) -> Safety | None:
    """The safety of the rule's fix (``FIX``, else ``TEXT_FIX``); ``None`` when it has none."""
    fix = getattr(rule, "FIX", None)
    return fix.safety if fix is not None else getattr(rule, "TEXT_FIX", None)


def fix_safety_text(rule: ModuleType) -> str:
    """The rule's fix as the listing and the documents say it: ``safe``, ``unsafe``, ``none``,
    or ``safe/unsafe`` for a slip undone (IN06x), which is safe only for an exact fit: a real
    part's likely slip, or one whose centre of mass is corrected too, gets an unsafe fix
    (:mod:`inertia_kit.lint.fixing`)."""
    safety = fix_safety(rule)
    fix = getattr(rule, "FIX", None)
    if safety is Safety.SAFE and fix is not None and fix.how == "slip":
        return "safe/unsafe"
    return "none" if safety is None else str(safety)


def supersedes(rule: ModuleType) -> tuple[str, ...]:
    """The codes whose findings on the same link a finding of ``rule`` replaces."""
    return tuple(getattr(rule, "SUPERSEDES", ()))


# --- selectors -------------------------------------------------------------------------------


def normalize_selector(text: str, known: Mapping[str, str] | None = None) -> str | None:
    """
    ``text`` as a selector: an upper-case code or code prefix (``IN012``, ``IN01``, ``IN``) that
    some rule's code starts with, or a rule name; ``None`` when it selects no rule. ``known``:
    ``code -> name`` (default: :func:`names`).
    """
    known = names() if known is None else known
    text = text.strip()
    if CODE.fullmatch(text):
        prefix = text.upper()
        return prefix if any(code.startswith(prefix) for code in known) else None
    return text if text in known.values() else None


def selects(selectors: Iterable[str], code: str, name: str) -> bool:
    """Whether a selector (a code, a code prefix or a name) picks the rule ``code``/``name``."""
    return any(code.startswith(s.upper()) or s == name for s in selectors)


def suggestions(text: str, known: Mapping[str, str]) -> list[str]:
    """
    What ``text`` may have meant: for a code, the zero-padded code (``IN12`` → ``IN012``); for
    a name, the nearest names.
    """
    text = text.strip()
    if re.fullmatch(r"(?i)IN[0-9]{1,2}", text):
        padded = "IN" + text[2:].zfill(3)
        return [padded] if padded in known else []
    import difflib  # an unknown name only: not imported by every run

    return difflib.get_close_matches(text, list(known.values()), n=3, cutoff=0.75)


def selector_error(text: str, known: Mapping[str, str]) -> str:
    """Why ``text`` is no selector, with what it may have meant."""
    close = suggestions(text, known)
    hint = f" (did you mean {', '.join(f'`{c}`' for c in close)}?)" if close else ""
    return f"`{text}` is not a rule code, code prefix or rule name{hint}"
