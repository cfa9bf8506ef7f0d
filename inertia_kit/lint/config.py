"""
Configuration: ``[tool.inertia-kit]`` in ``pyproject.toml``, or the same keys at the top level of
``.inertia-kit.toml``.

A linted file gets the configuration nearest to it: its folder, then each parent folder, where a
``.inertia-kit.toml`` wins over a ``pyproject.toml`` in the same folder and a ``pyproject.toml``
without ``[tool.inertia-kit]`` is passed over (ruff's discovery). ``--config PATH`` names one
file for every linted file instead.

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
    [tool.inertia-kit.per-file-ignores]
    "urdf/legacy/*.xacro" = ["IN02"]  # globs relative to this file's folder; no "/": any folder
    [tool.inertia-kit.rules.IN012]    # a code or a rule name
    severity = "error"
    floor = 1e-7                      # the rule's own options, checked against its OPTIONS
    [tool.inertia-kit.links.gripper]  # for inertia-fill: a density or a mass per link
    density = 2700.0
"""

from __future__ import annotations

import difflib
import functools
import math
import os
import re
import sys
import typing
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from inertia_kit.errors import ConfigError
from inertia_kit.lint.findings import Severity

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - exercised on Python 3.10 only
    import tomli as tomllib

CONFIG_NAME = ".inertia-kit.toml"
PYPROJECT = "pyproject.toml"

KEYS = (
    "select",
    "extend-select",
    "ignore",
    "per-file-ignores",
    "fail-on",
    "engines",
    "rules",
    "links",
)
LINK_KEYS = ("density", "mass")
_CODE = re.compile(r"IN[0-9]{0,3}", re.IGNORECASE)


# --- the rule catalog, as selectors see it ----------------------------------------------------


def planned_rules() -> dict[str, str]:
    """``code -> name`` from the registry's module names (``in012_inertia_too_small``)."""
    from inertia_kit.lint.rules import RULE_MODULES

    return {module[:5].upper(): module[6:].replace("_", "-") for module in RULE_MODULES}


def catalog() -> dict[str, str]:
    """
    ``code -> name`` of every rule: the registry's planned modules and the rules that exist,
    whose own ``NAME`` wins. Imports the rules.
    """
    from inertia_kit.lint import rules

    known = planned_rules()
    known.update({rule.CODE: rule.NAME for rule in rules.load_rules()})
    return known


def normalize_selector(text: str, known: Mapping[str, str] | None = None) -> str | None:
    """
    ``text`` as a selector: an upper-case code or code prefix (``IN012``, ``IN01``, ``IN``) that
    some rule's code starts with, or a rule name; ``None`` when it selects no rule.
    """
    known = catalog() if known is None else known
    text = text.strip()
    if _CODE.fullmatch(text):
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
    return difflib.get_close_matches(text, list(known.values()), n=3, cutoff=0.75)


def selector_error(text: str, known: Mapping[str, str]) -> str:
    """Why ``text`` is no selector, with what it may have meant."""
    close = suggestions(text, known)
    hint = f" (did you mean {', '.join(f'`{c}`' for c in close)}?)" if close else ""
    return f"`{text}` is no rule code, code prefix or rule name{hint}"


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
        regex = _glob_regex(self.pattern)
        absolute = os.path.abspath(path)
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


# --- reading ----------------------------------------------------------------------------------


def load_config(path: str | Path) -> Config:
    """
    Read one configuration file: ``pyproject.toml`` (its ``[tool.inertia-kit]`` table, which
    must exist) or any other name (``.inertia-kit.toml``: the keys at the top level).
    """
    path = Path(path)
    document = _read_toml(path)
    if path.name == PYPROJECT:
        table = document.get("tool", {}).get("inertia-kit")
        if table is None:
            raise ConfigError(f"{path}: no [tool.inertia-kit] table")
        return parse_config(table, path, prefix="tool.inertia-kit.")
    return parse_config(document, path)


def _read_toml(path: Path) -> dict[str, Any]:
    try:
        text = path.read_bytes().decode("utf-8")
    except FileNotFoundError:
        raise ConfigError(f"{path}: no such configuration file") from None
    except IsADirectoryError:
        raise ConfigError(f"{path}: is a directory, not a configuration file") from None
    except OSError as error:
        raise ConfigError(f"{path}: cannot read: {error.strerror or error}") from None
    except UnicodeDecodeError as error:
        raise ConfigError(f"{path}: not UTF-8 text: {error.reason}") from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ConfigError(f"{path}: invalid TOML: {error}") from None


def find_config(folder: str | Path) -> Path | None:
    """The configuration file that applies in ``folder``: the nearest, looking upward."""
    folder = Path(os.path.abspath(folder))
    for candidate in (folder, *folder.parents):
        own = candidate / CONFIG_NAME
        if own.is_file():
            return own
        pyproject = candidate / PYPROJECT
        if pyproject.is_file() and _has_section(pyproject):
            return pyproject
    return None


def _has_section(pyproject: Path) -> bool:
    try:
        data = pyproject.read_bytes()
    except OSError:
        return False
    if b"inertia-kit" not in data:  # most pyproject.toml files: no need to parse them
        return False
    return "inertia-kit" in _read_toml(pyproject).get("tool", {})


class ConfigFinder:
    """
    The configuration of each linted file: ``--config`` for all, else the nearest file,
    discovered once per folder and read once per file.
    """

    def __init__(self, explicit: str | Path | None = None):
        self.explicit = None if explicit is None else load_config(explicit)
        self._by_folder: dict[str, Path | None] = {}
        self._by_file: dict[Path, Config] = {}

    def for_file(self, path: str | Path) -> Config:
        if self.explicit is not None:
            return self.explicit
        folder = os.path.dirname(os.path.abspath(path))
        if folder not in self._by_folder:
            self._by_folder[folder] = find_config(folder)
        found = self._by_folder[folder]
        if found is None:
            return Config()
        if found not in self._by_file:
            self._by_file[found] = load_config(found)
        return self._by_file[found]


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
    known = catalog()
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
    )


def _rule_tables(
    where: _Where, rules_table: Any, known: Mapping[str, str]
) -> tuple[dict[str, dict[str, Any]], dict[str, Severity]]:
    from inertia_kit.lint import rules as registry

    loaded = {rule.CODE: rule for rule in registry.load_rules()}
    by_name = {rule.NAME: rule for rule in loaded.values()}
    options: dict[str, dict[str, Any]] = {}
    severities: dict[str, Severity] = {}
    seen: set[str] = set()
    for key, settings in where.table(rules_table, "rules").items():
        rule = loaded.get(key.upper()) if _CODE.fullmatch(key) else by_name.get(key)
        section = f"rules.{_quote(key)}"
        if rule is None:
            code = key.upper() if key.upper() in known else None
            code = code or next((c for c, n in known.items() if n == key), None)
            if code is not None:
                where.fail(section, f"rule {code} ({known[code]}) is not available in this version")
            where.fail(section, f"unknown rule: {selector_error(key, known)}")
        settings = where.table(settings, section)
        where.only(settings, ("severity", *rule.OPTIONS), section)
        if rule.CODE in seen:
            where.fail(section, f"{rule.CODE} ({rule.NAME}) is configured twice")
        seen.add(rule.CODE)
        values = {}
        for name, value in settings.items():
            if name == "severity":
                severities[rule.CODE] = where.severity(value, f"{section}.severity")
            else:
                values[name] = where.option(value, rule.OPTIONS[name], f"{section}.{name}")
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


_TYPE_NAMES = {float: "a number", int: "an integer", bool: "true or false", str: "a string"}


def _type_name(kind: Any) -> str:
    origin = typing.get_origin(kind)
    if origin in (list, tuple):
        (item, *_) = typing.get_args(kind) or (Any,)
        return f"a list of {_type_name(item).removeprefix('a ').removeprefix('an ')}s"
    if isinstance(kind, tuple):
        return " or ".join(_type_name(k) for k in kind)
    return _TYPE_NAMES.get(kind, getattr(kind, "__name__", str(kind)))


def _convert(value: Any, kind: Any) -> tuple[bool, Any]:
    """``(ok, value)``: ``value`` as ``kind`` (an option type from a rule's ``OPTIONS``)."""
    if isinstance(kind, tuple):
        for option in kind:
            ok, converted = _convert(value, option)
            if ok:
                return True, converted
        return False, None
    origin = typing.get_origin(kind)
    if origin in (list, tuple):
        if not isinstance(value, list):
            return False, None
        args = typing.get_args(kind)
        item = args[0] if args else Any
        items = [_convert(v, item) for v in value]
        if not all(ok for ok, _ in items):
            return False, None
        converted = [v for _, v in items]
        return True, tuple(converted) if origin is tuple else converted
    if kind is Any:
        return True, value
    if kind is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            return False, None
        return True, float(value)
    if kind is int:
        return (not isinstance(value, bool) and isinstance(value, int)), value
    if kind in (list, tuple):
        return isinstance(value, list), (tuple(value) if kind is tuple else value)
    return isinstance(value, kind), value


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
            selector = normalize_selector(item, known)
            if selector is None:
                self.fail(key, selector_error(item, known))
            selectors.append(selector)
        return tuple(selectors)

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

    def severity(self, value: Any, key: str) -> Severity:
        try:
            if not isinstance(value, str):
                raise ValueError
            return Severity.parse(value)
        except ValueError:
            self.fail(key, f'expected "error", "warning" or "info", got {_shown(value)}')

    def option(self, value: Any, kind: Any, key: str) -> Any:
        ok, converted = _convert(value, kind)
        if not ok:
            self.fail(key, f"expected {_type_name(kind)}, got {_shown(value)}")
        return converted

    def positive(self, value: Any, key: str) -> float:
        ok, number = _convert(value, float)
        if not ok or not math.isfinite(number) or number <= 0:
            self.fail(key, f"expected a positive number, got {_shown(value)}")
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
