"""
Command-line entry points. The click commands are thin; this is the only module that knows
exit codes: 0 success, 1 findings (lint) or changes (fill), 2 bad input or usage.
"""

from __future__ import annotations

import os

# the CLI runs on every commit: one BLAS thread starts faster and our products are small;
# set before numpy is first imported, unless the user chose
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import textwrap
from collections.abc import Callable
from typing import Any

import click

from inertia_kit.version import __version__


class UsageError(click.ClickException):
    """Bad input, usage or configuration: exit 2 (click's default of 1 would read as findings)."""

    exit_code = 2

    def show(self, file: Any = None) -> None:
        click.echo(f"error: {self.format_message()}", err=True)


@click.group(context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="inertia-kit")
def main() -> None:
    """inertia-kit: physically right <inertial> blocks for URDF and xacro robot descriptions."""


# --- inertia-kit mass ------------------------------------------------------------------------


@main.group("mass")
def mass_group() -> None:
    """
    Mass properties of a primitive or a mesh: mass, centre of mass, the inertia tensor about
    the centre of mass (and about any point), and a ready-to-paste URDF <inertial> block.

    \b
    Examples:
      inertia-kit mass cylinder --radius 0.35 --length 0.4 --density 1024 --about 0 0 -0.2
      inertia-kit mass mesh part.stl --density 2700 --scale 0.001
    """


def _common_options(command: Callable) -> Callable:
    options = [
        click.option(
            "--density",
            type=float,
            default=None,
            help="Uniform density, kg/m³ (default 1000 unless --mass is given).",
        ),
        click.option("--mass", "mass_kg", type=float, default=None, help="Total mass, kg."),
        click.option(
            "--xyz",
            nargs=3,
            type=float,
            default=(0.0, 0.0, 0.0),
            help="Place the shape: its origin in the link frame, m (as a URDF <origin xyz>).",
        ),
        click.option(
            "--rpy",
            nargs=3,
            type=float,
            default=(0.0, 0.0, 0.0),
            help="Place the shape: roll pitch yaw, rad (as a URDF <origin rpy>).",
        ),
        click.option(
            "--about",
            nargs=3,
            type=float,
            default=None,
            help="Also report the tensor about this point of the link frame, m.",
        ),
        click.option(
            "--about-rpy",
            nargs=3,
            type=float,
            default=None,
            help="...and in the axes of a frame rotated by these roll pitch yaw, rad.",
        ),
        click.option(
            "--format",
            "output_format",
            type=click.Choice(["text", "json"]),
            default="text",
            show_default=True,
        ),
    ]
    for option in reversed(options):
        command = option(command)
    return command


def _run_primitive(description: dict[str, Any], build: Callable[..., Any], **options: Any) -> None:
    from inertia_kit.report.mass import Part

    try:
        part = Part(description, build(density=1.0))  # at unit density the mass is the volume
    except ValueError as error:
        raise UsageError(str(error)) from None
    _show(part, options)


@mass_group.command("box")
@click.option("--size", nargs=3, type=float, required=True, help="Edge lengths x y z, m.")
@_common_options
def mass_box(size: tuple[float, float, float], **options: Any) -> None:
    """A solid box centred on its frame."""
    from inertia_kit.physics.primitives import box

    _run_primitive({"shape": "box", "size": list(size)}, lambda **kw: box(size, **kw), **options)


@mass_group.command("cylinder")
@click.option("--radius", type=float, required=True, help="m")
@click.option("--length", type=float, required=True, help="m, along z")
@_common_options
def mass_cylinder(radius: float, length: float, **options: Any) -> None:
    """A solid cylinder along z, centred on its frame (as URDF)."""
    from inertia_kit.physics.primitives import cylinder

    _run_primitive(
        {"shape": "cylinder", "radius": radius, "length": length},
        lambda **kw: cylinder(radius, length, **kw),
        **options,
    )


@mass_group.command("sphere")
@click.option("--radius", type=float, required=True, help="m")
@_common_options
def mass_sphere(radius: float, **options: Any) -> None:
    """A solid sphere."""
    from inertia_kit.physics.primitives import sphere

    _run_primitive(
        {"shape": "sphere", "radius": radius}, lambda **kw: sphere(radius, **kw), **options
    )


@mass_group.command("capsule")
@click.option("--radius", type=float, required=True, help="m")
@click.option("--length", type=float, required=True, help="m, of the cylinder between the caps")
@_common_options
def mass_capsule(radius: float, length: float, **options: Any) -> None:
    """A solid capsule along z: a cylinder capped by two hemispheres."""
    from inertia_kit.physics.primitives import capsule

    _run_primitive(
        {"shape": "capsule", "radius": radius, "length": length},
        lambda **kw: capsule(radius, length, **kw),
        **options,
    )


@mass_group.command("ellipsoid")
@click.option("--radii", nargs=3, type=float, required=True, help="Semi-axes a b c, m.")
@_common_options
def mass_ellipsoid(radii: tuple[float, float, float], **options: Any) -> None:
    """A solid ellipsoid with semi-axes along x, y, z."""
    from inertia_kit.physics.primitives import ellipsoid

    _run_primitive(
        {"shape": "ellipsoid", "radii": list(radii)}, lambda **kw: ellipsoid(radii, **kw), **options
    )


@mass_group.command("mesh")
@click.argument("path", type=click.Path(dir_okay=False))
@click.option(
    "--scale",
    default="1",
    show_default=True,
    help='URDF mesh scale: one factor or three, e.g. 0.001 or "0.001 0.001 0.001".',
)
@_common_options
def mass_mesh(path: str, scale: str, **options: Any) -> None:
    """A closed triangle mesh: STL, OBJ, DAE, PLY or GLB."""
    factors = _parse_scale(scale)
    from inertia_kit.errors import MeshError
    from inertia_kit.report.mass import mesh_part

    try:
        part = mesh_part(path, factors)
    except MeshError as error:
        raise UsageError(str(error)) from None
    _show(part, options)


def _parse_scale(text: str) -> tuple[float, float, float]:
    try:
        values = [float(part) for part in text.replace(",", " ").split()]
    except ValueError:
        raise UsageError(f"--scale takes one or three numbers, got {text!r}") from None
    if len(values) == 1:
        values *= 3
    if len(values) != 3:
        raise UsageError(f"--scale takes one or three numbers, got {len(values)}")
    return values[0], values[1], values[2]


def _show(part: Any, options: dict[str, Any]) -> None:
    from inertia_kit.report.mass import render

    try:
        text = render(part, **options)
    except ValueError as error:
        raise UsageError(str(error)) from None
    click.echo(text)


# --- options shared by report, lint and fill ---------------------------------------------------

package_path_option = click.option(
    "--package-path",
    "package_paths",
    multiple=True,
    type=click.Path(file_okay=False),
    help="Folder searched first for $(find pkg) and package://pkg (repeatable).",
)
xacro_arg_option = click.option(
    "--xacro-arg",
    "xacro_args",
    multiple=True,
    metavar="NAME:=VALUE",
    help="A xacro argument (repeatable).",
)


# --- inertia-kit report ----------------------------------------------------------------------


def _xacro_args(values: tuple[str, ...]) -> dict[str, str]:
    args = {}
    for value in values:
        name, sep, text = value.partition(":=")
        if not sep or not name:
            raise UsageError(f"--xacro-arg takes NAME:=VALUE, got {value!r}")
        args[name] = text
    return args


@main.command("report")
@click.argument("path", type=click.Path(dir_okay=False))
@click.option(
    "--format",
    "output_format",
    type=click.Choice(["text", "markdown", "json"]),
    default="text",
    show_default=True,
)
@click.option(
    "--lumped",
    is_flag=True,
    help="Instead, the bodies each engine simulates after fixed-joint lumping: their links, "
    "combined mass, COM and tensor, and the links the engine drops.",
)
@click.option(
    "--engine",
    "engines",
    multiple=True,
    metavar="NAMES",
    help="With --lumped: mujoco, gazebo, drake, pybullet, kdl or all, comma-separated "
    "(repeatable) [default: all].",
)
@package_path_option
@xacro_arg_option
def report_command(
    path: str,
    output_format: str,
    lumped: bool,
    engines: tuple[str, ...],
    package_paths: tuple[str, ...],
    xacro_args: tuple[str, ...],
) -> None:
    """A table of the robot's links: parent joint, declared mass, COM, principal moments,
    geometry and the source line to edit; and the robot's total mass. With --lumped, the
    bodies each engine simulates."""
    from inertia_kit.description.loader import load
    from inertia_kit.engines.verdicts import ENGINES, parse_engines
    from inertia_kit.errors import InputError
    from inertia_kit.report.robot import render, render_lumped

    if engines and not lumped:
        raise UsageError("--engine needs --lumped")
    try:
        chosen = parse_engines(engines) if engines else ENGINES
    except ValueError as error:
        raise UsageError(f"--engine: {error}") from None

    try:
        robot = load(path, xacro_args=_xacro_args(xacro_args), package_paths=package_paths)
    except InputError as error:
        raise UsageError(str(error)) from None
    if robot.fragment:
        click.echo(
            f"{path}: a xacro fragment (macros and properties only, to be included): no links",
            err=True,
        )
        return
    if lumped:
        click.echo(render_lumped(robot, chosen, output_format))
    else:
        click.echo(render(robot, output_format))


# --- inertia-lint (inertia-kit lint) ----------------------------------------------------------

OUTPUT_FORMATS = ("full", "concise", "json", "github", "sarif")


def _codes(values: tuple[str, ...]) -> tuple[str, ...]:
    """``--select IN01,IN020 --select IN002`` → ``("IN01", "IN020", "IN002")``."""
    return tuple(code.strip() for value in values for code in value.split(",") if code.strip())


def _colour() -> bool | None:
    """``None``: colour on a terminal only (click strips it elsewhere); NO_COLOR, FORCE_COLOR."""
    if os.environ.get("NO_COLOR"):
        return False
    if os.environ.get("FORCE_COLOR"):
        return True
    return None


@click.command("lint", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("paths", nargs=-1, type=click.Path())
@click.option(
    "--output-format",
    type=click.Choice(OUTPUT_FORMATS),
    default="full",
    show_default=True,
    help="How findings are printed (to stdout).",
)
@click.option(
    "--select",
    multiple=True,
    metavar="CODES",
    help="Rules to run: codes, code prefixes or names, comma-separated (repeatable). "
    "Replaces the configured select and ignore lists.",
)
@click.option(
    "--ignore",
    multiple=True,
    metavar="CODES",
    help="Rules not to run, as --select (repeatable); added to the configured ignore list.",
)
@click.option(
    "--engine",
    "engines",
    multiple=True,
    metavar="NAMES",
    help="Predict what these simulators do with each link (loads, silently changes or "
    "refuses it, with the engine's own message): mujoco, gazebo, drake, pybullet, kdl or all, "
    "comma-separated (repeatable). Replaces the configured `engines`; none by default.",
)
@click.option(
    "--fail-on",
    type=click.Choice(["error", "warning", "info"]),
    default=None,
    help="Lowest severity that makes the exit code 1 [default: fail-on in the "
    "configuration, else warning].",
)
@click.option(
    "--exit-zero",
    is_flag=True,
    help="Exit 0 even with findings (unreadable input or bad configuration still exit 2).",
)
@click.option(
    "--statistics", is_flag=True, help="Print how often each rule fired instead of the findings."
)
@click.option(
    "--config",
    "config_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Configuration file for every linted file (pyproject.toml or .inertia-kit.toml) "
    "instead of the nearest one.",
)
@package_path_option
@xacro_arg_option
@click.option("--explain", metavar="CODE", default=None, help="Print a rule's document and exit.")
@click.version_option(__version__, prog_name="inertia-lint")
@click.pass_context
def lint_command(ctx: click.Context, paths: tuple[str, ...], **options: Any) -> None:
    """
    Lint the <inertial> blocks of URDF and xacro robot descriptions: files, or folders (their
    *.urdf and *.xacro files; xacro fragments that only define macros are skipped).

    \b
    Exit codes: 0 no findings at or above --fail-on; 1 findings; 2 unreadable input,
    bad configuration or usage.
    \b
    Examples:
      inertia-lint urdf/
      inertia-lint --select IN01,IN020 --output-format concise robot.urdf.xacro
      inertia-lint --engine mujoco,gazebo robot.urdf
      inertia-lint --explain IN002
    """
    ctx.exit(lint(paths, **options))


def lint(
    paths: tuple[str, ...] | list[str],
    *,
    output_format: str = "full",
    select: tuple[str, ...] = (),
    ignore: tuple[str, ...] = (),
    engines: tuple[str, ...] = (),
    fail_on: str | None = None,
    exit_zero: bool = False,
    statistics: bool = False,
    config_path: str | None = None,
    package_paths: tuple[str, ...] = (),
    xacro_args: tuple[str, ...] = (),
    explain: str | None = None,
) -> int:
    """``inertia-lint``: print what it finds; return the exit code."""
    if explain is not None:
        from inertia_kit.lint.output import explain as document

        try:
            click.echo(document(explain), nl=False)
        except LookupError as error:
            click.echo(f"error: --explain: {error}", err=True)
            return 2
        return 0
    if not paths:
        click.echo("error: give files or folders to lint (or --explain CODE)", err=True)
        return 2

    from inertia_kit.errors import ConfigError
    from inertia_kit.lint.findings import Severity
    from inertia_kit.lint.merge import merge
    from inertia_kit.lint.output import render, summary
    from inertia_kit.lint.output import statistics as rule_statistics
    from inertia_kit.lint.runner import lint_paths

    try:
        results = lint_paths(
            paths,
            config=config_path,
            select=_codes(select),
            ignore=_codes(ignore),
            engines=engines or None,
            fail_on=None if fail_on is None else Severity.parse(fail_on),
            xacro_args=_xacro_args(xacro_args),
            package_paths=package_paths,
        )
    except (ConfigError, UsageError) as error:
        message = error.format_message() if isinstance(error, UsageError) else str(error)
        click.echo(f"error: {message}", err=True)
        return 2

    run = merge(results)
    for level, text in run.messages:
        click.echo(f"{level}: {text}", err=True)
    if not results:
        click.echo(
            f"warning: no robot descriptions (*.urdf, *.xacro) in {', '.join(paths)}", err=True
        )
    if statistics:
        output = rule_statistics(run.findings, as_json=output_format == "json")
    else:
        output = render(run.findings, output_format, errors=run.errors, style=click.style)
    click.echo(output, nl=False, color=_colour())
    click.echo(summary(run.findings, run.checked, len(run.errors)), err=True)
    if run.errors:
        return 2
    return 1 if run.failing and not exit_zero else 0


main.add_command(lint_command)
lint_main = lint_command


# --- inertia-fill (inertia-kit fill) ---------------------------------------------------------


def _material_help() -> str:
    from inertia_kit.fill.materials import materials_text

    return f"Density from a material: {materials_text()}."


@click.command("fill", context_settings={"help_option_names": ["-h", "--help"]})
@click.argument("paths", nargs=-1, type=click.Path())
@click.option(
    "--density",
    type=float,
    default=None,
    metavar="KG_PER_M3",
    help="Uniform density for links without a known mass, kg/m³ [default: 1000].",
)
@click.option("--material", default=None, metavar="NAME", help=_material_help())
@click.option(
    "--mass",
    "mass_options",
    multiple=True,
    metavar="LINK=KG",
    help="A link's mass, kg; its tensor is scaled to it (repeatable).",
)
@click.option(
    "--total-mass",
    type=float,
    default=None,
    metavar="KG",
    help="The robot's total mass, kg: the links without a known mass share what the others "
    "leave, in proportion to their volume (instead of --density).",
)
@click.option(
    "--config",
    "config_path",
    default=None,
    type=click.Path(dir_okay=False),
    metavar="FILE",
    help="Configuration file whose [links.NAME] tables give a link's density or mass "
    "[default: the nearest pyproject.toml with [tool.inertia-kit], or .inertia-kit.toml].",
)
@click.option(
    "--fix",
    type=click.Choice(["missing", "invalid", "all"]),
    default="missing",
    show_default=True,
    help="missing: links that need an <inertial> and have none; invalid: also replace "
    "impossible ones (a valid declared mass is kept); all: every link with geometry.",
)
@click.option("--diff", "show_diff", is_flag=True, help="Print a unified diff; write nothing.")
@click.option("--check", is_flag=True, help="Write nothing; exit 1 if a file would change.")
@click.option(
    "-o",
    "--output",
    default=None,
    type=click.Path(dir_okay=False),
    metavar="OUT",
    help="Write the filled robot to OUT and leave PATH (exactly one) untouched: a URDF's own "
    "text, edited; for xacro, the fully expanded URDF, where links made by macros are filled "
    "too. OUT is always written; exit 1 if links were filled or refused, 0 if none needed it.",
)
@package_path_option
@xacro_arg_option
@click.version_option(__version__, prog_name="inertia-fill")
@click.pass_context
def fill_command(ctx: click.Context, paths: tuple[str, ...], **options: Any) -> None:
    """
    Write <inertial> blocks computed from each link's geometry (collision shapes, else visual
    ones, at uniform density) into URDF files, as small text edits: comments, layout, quoting
    and line endings are kept.

    \b
    Exit codes: 0 nothing to do; 1 a file was (or would be) changed, or a link was refused;
    2 unreadable input or bad usage. With -o: 1 when links were (or would be) filled into OUT
    or refused, 0 when none needed filling (OUT is written all the same).
    \b
    Examples:
      inertia-fill robot.urdf
      inertia-fill --material aluminium --mass gripper=0.35 --diff robot.urdf
      inertia-fill --fix invalid --check urdf/*.urdf
      inertia-fill --density 1200 -o robot_filled.urdf robot.urdf.xacro
      inertia-fill --total-mass 12.5 --fix all robot.urdf.xacro
    """
    ctx.exit(fill(paths, **options))


def _masses(values: tuple[str, ...]) -> dict[str, float]:
    masses = {}
    for value in values:
        name, sep, text = value.partition("=")
        try:
            kg = float(text)
        except ValueError:
            kg = float("nan")
        if not sep or not name or not (kg > 0 and kg != float("inf")):
            raise UsageError(f"--mass takes LINK=KG with a positive mass, got {value!r}")
        masses[name] = kg
    return masses


def fill(
    paths: tuple[str, ...] | list[str],
    *,
    density: float | None = None,
    material: str | None = None,
    mass_options: tuple[str, ...] = (),
    total_mass: float | None = None,
    config_path: str | None = None,
    fix: str = "missing",
    show_diff: bool = False,
    check: bool = False,
    output: str | None = None,
    package_paths: tuple[str, ...] = (),
    xacro_args: tuple[str, ...] = (),
) -> int:
    """``inertia-fill``: plan every file, then write (not for ``--diff``/``--check``)."""
    from inertia_kit.errors import ConfigError, InputError
    from inertia_kit.fill.output import plan_fill_output, write_output
    from inertia_kit.fill.plan import apply, plan_fill
    from inertia_kit.fill.policy import density_option, per_link, unknown_links
    from inertia_kit.lint.config import ConfigFinder

    try:
        if not paths:
            raise UsageError("give URDF files to fill")
        if output is not None and len(paths) != 1:
            raise UsageError(f"-o takes exactly one PATH, got {len(paths)}")
        arguments = _xacro_args(xacro_args)
        try:
            density = density_option(density, material, total_mass)
        except ValueError as error:
            raise UsageError(str(error)) from None
        masses = _masses(mass_options)
        finder = ConfigFinder(config_path)
    except UsageError as error:
        click.echo(f"error: {error.format_message()}", err=True)
        return 2
    except ConfigError as error:
        click.echo(f"error: {error}", err=True)
        return 2

    plans, failed = [], False
    options = {
        "density": density,
        "fix": fix,
        "package_paths": package_paths,
        "xacro_args": arguments,
        "total_mass": total_mass,
    }
    for path in paths:
        try:
            per_file = per_link(finder.for_file(path).links, masses)
            if output is not None:
                plans.append(plan_fill_output(path, output, **options, **per_file))
            else:
                plans.append(plan_fill(path, **options, **per_file))
        except ConfigError as error:
            click.echo(f"error: {error}", err=True)
            return 2
        except InputError as error:
            click.echo(f"error: {error}", err=True)
            failed = True
    unknown = unknown_links(masses, plans)
    if unknown:
        click.echo(f"error: --mass names no link in the files: {', '.join(unknown)}", err=True)
        return 2

    write = not (show_diff or check)
    changed = refused = False
    for plan in plans:
        for note in plan.notes:
            click.echo(f"note: {plan.path}: {note}", err=True)
        if show_diff and plan.changed:
            click.echo(plan.diff(), nl=False)
        filled = plan.changed_links
        if filled or (plan.input_path is not None and write):
            try:
                if write:
                    (apply if plan.input_path is None else write_output)(plan)
            except InputError as error:
                click.echo(f"error: {error}", err=True)
                failed = True
            else:
                changed = changed or bool(filled)
                click.echo(_fill_line(plan, write), err=True)
        for refusal in plan.refused:
            refused = True
            click.echo(f"{plan.path}: link `{refusal.link}` not filled: {refusal.reason}", err=True)
            if refusal.block is not None:
                click.echo(textwrap.indent(refusal.block, "    "), err=True)
    if failed:
        return 2
    return 1 if changed or refused else 0


def _fill_line(plan: Any, write: bool) -> str:
    """``Filled 2 links in robot.urdf: arm 1.2 kg, ...`` (``of IN into OUT`` for ``-o``)."""
    filled = plan.changed_links
    where = (
        f"in {plan.path}" if plan.input_path is None else f"of {plan.input_path} into {plan.path}"
    )
    if not filled:
        return f"Wrote {plan.path}: nothing to fill in {plan.input_path}"
    verb = "Filled" if write else "Would fill"
    count = f"{len(filled)} link{'s' if len(filled) != 1 else ''}"
    what = ", ".join(f"{f.link} {f.mass_text} kg" for f in filled)
    return f"{verb} {count} {where}: {what}"


main.add_command(fill_command)
fill_main = fill_command
