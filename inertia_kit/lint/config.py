"""
Configuration: ``[tool.inertia-kit]`` in ``pyproject.toml``, or the same keys at the top level of
``.inertia-kit.toml``.

This module holds the keys, the values they become and their validation; which file applies to
a linted file, and reading it, is :mod:`inertia_kit.lint.config_files`.

Everything is checked when the file is read: an unknown key anywhere, a value of the wrong type,
an unknown rule, code or option raises :class:`~inertia_kit.errors.ConfigError` naming the file
and the key (the command exits 2).

::

    [tool.inertia-kit]
    select = ["IN0"]                  # codes, code prefixes or rule names
    extend-select = []                # added to select
    ignore = ["IN013"]
    fail-on = "warning"               # error | warning | info
    engines = ["mujoco"]              # verdict rules (IN07x) of: mujoco gazebo drake pybullet
                                      # kdl, or "all"; none by default
    fix = false                       # inertia-lint applies safe fixes (as --fix)
    unsafe-fixes = false              # ... and unsafe ones (as --unsafe-fixes)
    fixable = ["IN0"]                 # rules whose fixes may be applied (default: all)
    unfixable = ["IN021"]             # rules whose fixes are never applied
    exclude = ["generated/"]          # gitignore-style, relative to this file's folder;
                                      # replaces the defaults (lint.exclusion)
    extend-exclude = ["*.gen.urdf"]   # added to exclude (and the defaults)
    respect-gitignore = true          # .gitignore files and .git/info/exclude
    force-exclude = false             # exclude files given by name too (pre-commit)
    redact-environment = false        # keep what xacro read from the environment out of
                                      # every output (as --redact-env)
    [tool.inertia-kit.per-file-ignores]
    "urdf/legacy/*.xacro" = ["IN02"]  # globs relative to this file's folder; no "/": any folder
    [tool.inertia-kit.rules.IN012]    # a code or a rule name
    severity = "error"
    min_moment = 1e-7                 # the rule's own options, checked against its OPTIONS
    [tool.inertia-kit.links.gripper]  # for inertia-fill: a density or a mass per link
    density = 2700.0
    [tool.inertia-kit.xacro]          # limits of a xacro expansion (0: none); the
    timeout = 30                      # environment's INERTIA_KIT_XACRO_LIMITS and
    memory = 1024                     # --xacro-limit override them
    elements = 50000
"""

from __future__ import annotations

import functools
import os
import re
import typing
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inertia_kit.errors import ConfigError
from inertia_kit.lint import catalog
from inertia_kit.lint.findings import Severity
from inertia_kit.lint.options import Option, convert, out_of_range, type_name

KEYS = (
    "select",
    "extend-select",
    "ignore",
    "per-file-ignores",
    "fail-on",
    "engines",
    "rules",
    "links",
    "xacro",
    "fix",
    "unsafe-fixes",
    "fixable",
    "unfixable",
    "exclude",
    "extend-exclude",
    "respect-gitignore",
    "force-exclude",
    "redact-environment",
)
LINK_KEYS = ("density", "mass")


# --- values -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class PerFileIgnore:
    """
    Codes ignored in the files a glob matches. ``pattern`` is relative to ``base`` (the folder
    of the configuration file); one without ``/`` matches a file name in any folder. ``**``
    matches any number of folders, ``*`` and ``?`` stay inside one.
    """

    pattern: str
    base: str
    codes: tuple[str, ...]

    def matches(self, path: str | Path) -> bool:
        from inertia_kit.lint.stand_in import named

        regex = _glob_regex(self.pattern)
        absolute = os.path.abspath(named(path))  # a robot read from stdin: the name it stands for
        if regex.match(Path(absolute).name) and "/" not in self.pattern:
            return True
        if os.path.isabs(self.pattern):
            return regex.match(Path(absolute).as_posix()) is not None
        try:
            relative = Path(absolute).relative_to(self.base).as_posix()
        except ValueError:
            return False
        return regex.match(relative) is not None


@dataclass(frozen=True)
class LinkSettings:
    """What ``inertia-fill`` assumes for one link: a uniform density (kg/m³) or a mass (kg)."""

    density: float | None = None
    mass: float | None = None


@dataclass(frozen=True)
class Config:
    """One configuration file, validated; ``path`` is ``None`` for the defaults."""

    path: str | None = None
    select: tuple[str, ...] | None = None
    extend_select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    per_file_ignores: tuple[PerFileIgnore, ...] = ()
    fail_on: Severity | None = None
    options: dict[str, dict[str, Any]] = field(default_factory=dict)  # code -> option -> value
    severities: dict[str, Severity] = field(default_factory=dict)  # code -> severity
    links: dict[str, LinkSettings] = field(default_factory=dict)
    engines: tuple[str, ...] = ()  # engines whose verdict rules run (IN07x)
    xacro: dict[str, float] = field(default_factory=dict)  # xacro limits set here: name -> value
    fix: bool | None = None  # apply safe fixes (``--fix``)
    unsafe_fixes: bool | None = None  # also unsafe ones (``--unsafe-fixes``)
    fixable: tuple[str, ...] | None = None  # rules whose fixes may be applied (None: all)
    unfixable: tuple[str, ...] = ()  # rules whose fixes are never applied
    exclude: tuple[str, ...] | None = None  # folder walk: None keeps the defaults
    extend_exclude: tuple[str, ...] = ()
    respect_gitignore: bool | None = None
    force_exclude: bool | None = None
    redact_environment: bool = False  # --redact-env (description.redaction)


# --- validation -------------------------------------------------------------------------------


def parse_config(table: Mapping[str, Any], path: str | Path, prefix: str = "") -> Config:
    """Validate a configuration table read from ``path``; ``prefix`` is how its keys are shown."""
    path = Path(path)
    where = _Where(path, prefix)
    where.only(table, KEYS, "")
    if not prefix and "tool" in table:
        where.fail(
            "tool",
            "unknown key (in .inertia-kit.toml the keys stand at the top level, "
            "without [tool.inertia-kit])",
        )
    known = catalog.names()
    select = None
    if "select" in table:
        select = where.selectors(table["select"], "select", known)
    per_file: list[PerFileIgnore] = []
    patterns = where.table(table.get("per-file-ignores", {}), "per-file-ignores")
    base = str(Path(os.path.abspath(path)).parent)
    for pattern, codes in patterns.items():
        key = f"per-file-ignores.{_quote(pattern)}"
        if not pattern.strip():
            where.fail(key, "an empty glob matches no file")
        per_file.append(PerFileIgnore(pattern.strip(), base, where.selectors(codes, key, known)))
    fail_on = None
    if "fail-on" in table:
        fail_on = where.severity(table["fail-on"], "fail-on")
    options, severities = _rule_tables(where, table.get("rules", {}), known)
    return Config(
        path=str(path),
        select=select,
        extend_select=where.selectors(table.get("extend-select", []), "extend-select", known),
        ignore=where.selectors(table.get("ignore", []), "ignore", known),
        per_file_ignores=tuple(per_file),
        fail_on=fail_on,
        options=options,
        severities=severities,
        links=_links(where, table.get("links", {})),
        engines=where.engines(table.get("engines", []), "engines"),
        xacro=_xacro_limits(where, table.get("xacro", {})),
        fix=where.flag(table.get("fix"), "fix"),
        unsafe_fixes=where.flag(table.get("unsafe-fixes"), "unsafe-fixes"),
        fixable=where.selectors(table["fixable"], "fixable", known) if "fixable" in table else None,
        unfixable=where.selectors(table.get("unfixable", []), "unfixable", known),
        exclude=where.patterns(table["exclude"], "exclude") if "exclude" in table else None,
        extend_exclude=where.patterns(table.get("extend-exclude", []), "extend-exclude"),
        respect_gitignore=where.flag(table.get("respect-gitignore"), "respect-gitignore"),
        force_exclude=where.flag(table.get("force-exclude"), "force-exclude"),
        redact_environment=bool(where.flag(table.get("redact-environment"), "redact-environment")),
    )


def _xacro_limits(where: _Where, xacro_table: Any) -> dict[str, float]:
    from inertia_kit.description.xacro_limits import check_limit

    settings = where.table(xacro_table, "xacro")
    where.only(settings, ("timeout", "memory", "elements"), "xacro")
    values = {}
    for name, value in settings.items():
        if isinstance(value, str):
            where.fail(f"xacro.{name}", f"expected a number (0: no limit), got {_shown(value)}")
        try:
            values[name] = check_limit(name, value)
        except ValueError as error:
            where.fail(f"xacro.{name}", str(error))
    return values


def _rule_tables(
    where: _Where, rules_table: Any, known: Mapping[str, str]
) -> tuple[dict[str, dict[str, Any]], dict[str, Severity]]:
    options: dict[str, dict[str, Any]] = {}
    severities: dict[str, Severity] = {}
    seen: set[str] = set()
    for key, settings in where.table(rules_table, "rules").items():
        rule = catalog.find(key)
        section = f"rules.{_quote(key)}"
        if rule is None:
            where.fail(section, f"unknown rule: {catalog.selector_error(key, known)}")
        settings = where.table(settings, section)
        declared = {option.name: option for option in catalog.options(rule)}
        where.only(settings, ("severity", *declared), section)
        if rule.CODE in seen:
            where.fail(section, f"{rule.CODE} ({rule.NAME}) is configured twice")
        seen.add(rule.CODE)
        values = {}
        for name, value in settings.items():
            if name == "severity":
                severities[rule.CODE] = where.severity(value, f"{section}.severity")
            else:
                values[name] = where.option(value, declared[name], f"{section}.{name}")
        if values:
            options[rule.CODE] = values
    return options, severities


def _links(where: _Where, links_table: Any) -> dict[str, LinkSettings]:
    links = {}
    for name, settings in where.table(links_table, "links").items():
        section = f"links.{_quote(name)}"
        settings = where.table(settings, section)
        where.only(settings, LINK_KEYS, section)
        if len(settings) != 1:
            where.fail(section, "give the link a density (kg/m³) or a mass (kg): exactly one")
        values = {key: where.positive(value, f"{section}.{key}") for key, value in settings.items()}
        links[name] = LinkSettings(**values)
    return links


def _quote(key: str) -> str:
    """A key as TOML writes it in a dotted path."""
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else f'"{key}"'


@dataclass(frozen=True)
class _Where:
    """Checks values of one file, and names the file and key in every error."""

    path: Path
    prefix: str

    def fail(self, key: str, message: str) -> typing.NoReturn:
        raise ConfigError(f"{self.path}: `{self.prefix}{key}`: {message}")

    def only(self, table: Mapping[str, Any], allowed: Iterable[str], section: str) -> None:
        allowed = tuple(allowed)
        for key in table:
            if key not in allowed:
                import difflib  # a misspelt key only: not imported by every run

                close = difflib.get_close_matches(key, allowed, n=1)
                hint = f" (did you mean `{close[0]}`?)" if close else ""
                expected = ", ".join(f"`{a}`" for a in allowed) or "none"
                self.fail(
                    f"{section}.{_quote(key)}" if section else _quote(key),
                    f"unknown key{hint}; known here: {expected}",
                )

    def table(self, value: Any, key: str) -> dict[str, Any]:
        if not isinstance(value, dict):
            self.fail(key, f"expected a table, got {_shown(value)}")
        return value

    def selectors(self, value: Any, key: str, known: Mapping[str, str]) -> tuple[str, ...]:
        if isinstance(value, str) or not isinstance(value, list):
            self.fail(
                key, f'expected a list of codes or names, e.g. ["IN012"], got {_shown(value)}'
            )
        selectors = []
        for item in value:
            if not isinstance(item, str):
                self.fail(key, f"expected codes or names, got {_shown(item)}")
            selector = catalog.normalize_selector(item, known)
            if selector is None:
                self.fail(key, catalog.selector_error(item, known))
            selectors.append(selector)
        return tuple(selectors)

    def patterns(self, value: Any, key: str) -> tuple[str, ...]:
        from inertia_kit.lint.exclusion import compile_patterns

        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self.fail(key, f'expected a list of patterns, e.g. ["generated/"], got {_shown(value)}')
        try:
            compile_patterns(value)
        except ValueError as error:
            self.fail(key, str(error))
        return tuple(value)

    def engines(self, value: Any, key: str) -> tuple[str, ...]:
        from inertia_kit.engines.vocabulary import ALL, ENGINES, parse_engines

        if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
            self.fail(
                key,
                f'expected a list of engine names, e.g. ["mujoco"] ({", ".join(ENGINES)} or '
                f'"{ALL}"), got {_shown(value)}',
            )
        try:
            return parse_engines(value)
        except ValueError as error:
            self.fail(key, str(error))

    def flag(self, value: Any, key: str) -> bool | None:
        if value is not None and not isinstance(value, bool):
            self.fail(key, f"expected true or false, got {_shown(value)}")
        return value

    def severity(self, value: Any, key: str) -> Severity:
        try:
            if not isinstance(value, str):
                raise ValueError
            return Severity.parse(value)
        except ValueError:
            self.fail(key, f'expected "error", "warning" or "info", got {_shown(value)}')

    def option(self, value: Any, option: Option, key: str) -> Any:
        ok, converted = convert(value, option.type)
        if not ok:
            self.fail(key, f"expected {type_name(option.type)}, got {_shown(value)}")
        wrong = out_of_range(converted, option)
        if wrong:
            self.fail(key, wrong)
        return converted

    def positive(self, value: Any, key: str) -> float:
        from inertia_kit.physics.numbers import usable

        ok, number = convert(value, float)
        if not ok or not usable(number, scale=True) or number <= 0:
            self.fail(key, f"expected a positive number from 1e-50 to 1e50, got {_shown(value)}")
        return number


def _shown(value: Any) -> str:
    """A TOML value as the user wrote it, more or less."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return f'"{value}"'
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "a list"
    return repr(value)


@functools.lru_cache(maxsize=256)
def _glob_regex(pattern: str) -> re.Pattern[str]:
    """A compiled regex for a glob: ``**`` any folders, ``*`` and ``?`` within one, ``[...]``."""
    out = []
    i = 0
    pattern = pattern.removeprefix("./")
    while i < len(pattern):
        if pattern.startswith("**/", i):
            out.append("(?:.*/)?")
            i += 3
            continue
        if pattern.startswith("**", i):
            out.append(".*")
            i += 2
            continue
        char = pattern[i]
        if char == "*":
            out.append("[^/]*")
        elif char == "?":
            out.append("[^/]")
        elif char == "[" and (end := pattern.find("]", i + 2)) > 0:
            body = pattern[i + 1 : end]
            negate = body.startswith("!")
            body = re.escape(body[1:] if negate else body).replace("\\-", "-")
            out.append(f"[{'^' if negate else ''}{body}]")
            i = end + 1
            continue
        else:
            out.append(re.escape(char))
        i += 1
    return re.compile("".join(out) + r"\Z")
