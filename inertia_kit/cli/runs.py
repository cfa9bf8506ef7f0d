"""
What one ``inertia-lint`` or ``inertia-fill`` run is asked to do, as one frozen value built once
from the command line and the configuration (:meth:`LintRun.parse`, :meth:`FillRun.parse`):
the commands read it, pass it down and print by it; nothing changes it. A bad option or
configuration is a :class:`~inertia_kit.cli.options.UsageError` (exit 2) when it is parsed,
before anything is read or linted.

``-`` (stdin) runs the same value on the stand-in file (:meth:`LintRun.on`), by
:mod:`inertia_kit.cli.stdin`, which reads what both values say about stdin.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

from inertia_kit.cli.options import UsageError, parse_codes, parse_xacro_args, parse_xacro_limits

if TYPE_CHECKING:
    from inertia_kit.lint.config import Config
    from inertia_kit.lint.config_files import ConfigFinder
    from inertia_kit.lint.discovery import Discovery
    from inertia_kit.lint.findings import Severity

#: formats a program reads: their findings are redacted before they are rendered, never after
MACHINE = ("json", "github", "sarif", "junit", "gitlab")
#: formats printed file by file as the files are linted (json and sarif are one document)
STREAMED = ("full", "concise", "github")
#: formats that show where a fix would go or what it would write (its edits, or the reason it
#: has no place to go): the others need only whether a finding has a fix, and of what safety
PLACES_FIXES = ("full", "json", "sarif")


def given_paths(paths: Sequence[str], stdin_filename: str | None) -> tuple[str, ...]:
    """
    The paths a run is on: ``-`` for stdin (``--stdin-filename`` alone implies it);
    ``UsageError`` when ``-`` comes with other paths.
    """
    if not paths and stdin_filename is not None:
        return ("-",)
    if "-" in paths and len(paths) != 1:
        raise UsageError("`-` (stdin) is the only path of a run: give no other files or folders")
    return tuple(paths)


def _configuration(options: Mapping[str, Any]) -> tuple[ConfigFinder, Discovery]:
    """The configuration of each file (``--config``, else the nearest) and the folder walk the
    discovery options ask for over it."""
    from inertia_kit.cli.discovery import discovery
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint.config_files import ConfigFinder

    try:
        finder = ConfigFinder(options.get("config_path"))
    except ConfigError as error:
        raise UsageError(str(error)) from None
    return finder, discovery(dict(options), finder)


@dataclass(frozen=True)
class LintRun:
    """
    One ``inertia-lint`` run. ``finder`` gives each file's configuration, ``walk`` what the
    folder walk leaves out; the next fields are what is linted (the options of
    :func:`~inertia_kit.lint.paths.linting`; ``None``: as each file's configuration says),
    the last ones how it is told.
    """

    paths: tuple[str, ...]
    finder: ConfigFinder
    walk: Discovery
    stdin_filename: str | None = None
    select: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    engines: tuple[str, ...] | None = None
    fail_on: Severity | None = None
    xacro_args: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()
    xacro_limits: dict[str, float] = field(default_factory=dict)
    fix: bool | None = None
    unsafe_fixes: bool | None = None
    diff: bool = False
    jobs: int | None = None
    follow_symlinks: bool = False
    output_format: str = "full"
    quiet: bool = False
    statistics: bool = False
    output_file: str | None = None
    add_noqa: bool = False
    exit_zero: bool = False
    redact_env: bool | None = None
    show_files: bool = False

    #: a robot on stdin that ``--force-exclude`` leaves out is not printed back
    echoes_excluded: ClassVar[bool] = False

    @classmethod
    def parse(cls, paths: Sequence[str], options: Mapping[str, Any]) -> LintRun:
        """The run the command line's ``paths`` and ``options`` (click's names) ask for."""
        from inertia_kit.lint.findings import Severity

        paths = given_paths(paths, options.get("stdin_filename"))
        if not paths:
            raise UsageError("give files or folders to lint (or --explain CODE)")
        if options.get("add_noqa") and paths == ("-",):
            raise UsageError("--add-noqa writes comments into files: not with `-` (stdin)")
        if options.get("add_noqa") and options.get("output_file") is not None:
            raise UsageError(
                "--output-file: --add-noqa writes comments into the files and prints no "
                "report to write; drop one of them"
            )
        finder, walk = _configuration(options)
        fail_on = options.get("fail_on")
        return cls(
            paths,
            finder,
            walk,
            stdin_filename=options.get("stdin_filename"),
            select=parse_codes(options.get("select", ())),
            ignore=parse_codes(options.get("ignore", ())),
            engines=tuple(options.get("engines", ())) or None,
            fail_on=None if fail_on is None else Severity.parse(fail_on),
            xacro_args=parse_xacro_args(options.get("xacro_args", ())),
            package_paths=tuple(options.get("package_paths", ())),
            xacro_limits=parse_xacro_limits(options.get("xacro_limits", ())),
            fix=options.get("fix"),
            unsafe_fixes=options.get("unsafe_fixes"),
            diff=bool(options.get("show_diff")),
            jobs=options.get("jobs"),
            follow_symlinks=bool(options.get("follow_symlinks")),
            output_format=options.get("output_format", "full"),
            quiet=bool(options.get("quiet")),
            statistics=bool(options.get("statistics")),
            output_file=options.get("output_file"),
            add_noqa=bool(options.get("add_noqa")),
            exit_zero=bool(options.get("exit_zero")),
            redact_env=options.get("redact_env"),
            show_files=bool(options.get("show_files")),
        )

    @property
    def reads_stdin(self) -> bool:
        return self.paths == ("-",)

    def on(self, path: str) -> LintRun:
        """This run on the stand-in of stdin: its report goes back through stdin's runner."""
        return dataclasses.replace(self, paths=(path,), output_file=None)

    def prints_text(self, configured: Config) -> bool:
        """Whether the run on stdin prints the resulting text (``--fix``, as configured)."""
        fix = configured.fix if self.fix is None else self.fix
        return not self.diff and bool(fix)

    @property
    def streams(self) -> bool:
        """Whether findings are printed file by file as the files are linted."""
        report = self.statistics or self.diff or self.output_file or self.add_noqa
        return self.output_format in STREAMED and not report

    @property
    def machine(self) -> bool:
        """Whether the format is read by a program (redacted before rendering, written as is)."""
        return self.output_format in MACHINE

    def redacts(self, path: str) -> bool:
        """Whether what the environment gave ``path``'s robot is kept out of the output."""
        from inertia_kit.cli.printing import redacting

        return redacting(self.redact_env, self.finder.for_file(path).redact_environment)

    def linting(self) -> dict[str, Any]:
        """The options of :func:`~inertia_kit.lint.paths.linting` (``on_error`` aside)."""
        return {
            "config": self.finder,
            "select": self.select,
            "ignore": self.ignore,
            "engines": self.engines,
            "fail_on": self.fail_on,
            "xacro_args": self.xacro_args,
            "package_paths": self.package_paths,
            "xacro_limits": self.xacro_limits,
            "fix": self.fix,
            "unsafe_fixes": self.unsafe_fixes,
            "diff": self.diff,
            "discovery": self.walk,
            "jobs": self.jobs,
            "follow_symlinks": self.follow_symlinks,
            "place_fixes": self.output_format in PLACES_FIXES,
        }


@dataclass(frozen=True)
class FillRun:
    """
    One ``inertia-fill`` run: ``density`` the one links without a known mass take (from
    ``--density`` or ``--material``; 1000 kg/m³), ``masses`` and ``links`` the links named
    (``--mass``, ``--link``), ``output`` ``-o OUT``; ``finder`` and ``walk`` as for
    :class:`LintRun`. ``-j`` is accepted and not used: fill runs in one process.
    """

    paths: tuple[str, ...]
    finder: ConfigFinder
    walk: Discovery
    stdin_filename: str | None = None
    density: float = 1000.0
    total_mass: float | None = None
    masses: dict[str, float] = field(default_factory=dict)
    links: tuple[str, ...] = ()
    fix: str = "missing"
    diff: bool = False
    check: bool = False
    output: str | None = None
    package_paths: tuple[str, ...] = ()
    xacro_args: dict[str, str] = field(default_factory=dict)
    xacro_limits: dict[str, float] = field(default_factory=dict)
    redact_env: bool | None = None
    follow_symlinks: bool = False
    show_files: bool = False

    #: no report file: what fill says goes to stderr, the text or diff to stdout
    output_file: ClassVar[None] = None

    @classmethod
    def parse(cls, paths: Sequence[str], options: Mapping[str, Any]) -> FillRun:
        """The run the command line's ``paths`` and ``options`` (click's names) ask for."""
        from inertia_kit.fill.policy import density_option

        paths = given_paths(paths, options.get("stdin_filename"))
        if not paths:
            raise UsageError("give URDF files or folders to fill")
        output = options.get("output")
        if output is not None and (len(paths) != 1 or os.path.isdir(paths[0])):
            raise UsageError(f"-o takes exactly one file PATH, got {', '.join(paths)}")
        xacro_args = parse_xacro_args(options.get("xacro_args", ()))
        xacro_limits = parse_xacro_limits(options.get("xacro_limits", ()))
        total_mass = options.get("total_mass")
        try:
            density = density_option(options.get("density"), options.get("material"), total_mass)
        except ValueError as error:
            raise UsageError(str(error)) from None
        masses = _masses(options.get("mass_options", ()))
        finder, walk = _configuration(options)
        return cls(
            paths,
            finder,
            walk,
            stdin_filename=options.get("stdin_filename"),
            density=density,
            total_mass=total_mass,
            masses=masses,
            links=tuple(options.get("link_options", ())),
            fix=options.get("fix", "missing"),
            diff=bool(options.get("show_diff")),
            check=bool(options.get("check")),
            output=output,
            package_paths=tuple(options.get("package_paths", ())),
            xacro_args=xacro_args,
            xacro_limits=xacro_limits,
            redact_env=options.get("redact_env"),
            follow_symlinks=bool(options.get("follow_symlinks")),
            show_files=bool(options.get("show_files")),
        )

    @property
    def reads_stdin(self) -> bool:
        return self.paths == ("-",)

    @property
    def writes(self) -> bool:
        """Whether the files are written (not ``--diff``, not ``--check``)."""
        return not (self.diff or self.check)

    @property
    def echoes_excluded(self) -> bool:
        """Whether a robot on stdin that ``--force-exclude`` leaves out is printed back
        unchanged (as formatters do)."""
        return self.writes

    def on(self, path: str) -> FillRun:
        """This run on the stand-in of stdin."""
        return dataclasses.replace(self, paths=(path,))

    def prints_text(self, configured: Config) -> bool:
        """Whether the run on stdin prints the filled text (not with ``--diff``, ``--check``,
        ``-o``)."""
        return self.writes and not self.output


def _masses(values: Sequence[str]) -> dict[str, float]:
    """``--mass LINK=KG`` options as ``{LINK: KG}``; ``UsageError`` otherwise."""
    from inertia_kit.physics.numbers import usable

    masses = {}
    for value in values:
        name, sep, text = value.partition("=")
        try:
            kg = float(text)
        except ValueError:
            kg = float("nan")
        if not sep or not name or not (kg > 0 and usable(kg, scale=True)):
            raise UsageError(
                f"--mass takes LINK=KG with a positive mass from 1e-50 to 1e50 kg, got {value!r}"
            )
        masses[name] = kg
    return masses
