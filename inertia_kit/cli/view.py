"""``inertia-kit view``: the review page of one robot, and a PNG of it on request."""

from __future__ import annotations

import re
from typing import Any

import click

from inertia_kit.cli.guard import GuardedCommand
from inertia_kit.cli.options import (
    HELP,
    UsageError,
    follow_symlinks_option,
    package_path_option,
    parse_codes,
    parse_xacro_args,
    parse_xacro_limits,
    xacro_arg_option,
    xacro_limit_option,
)
from inertia_kit.cli.printing import keep_out, redact_env_option, redacting, say

DEFAULT_BUDGET = 300_000


def _size(value: str) -> tuple[int, int]:
    """``--png-size 1280x800`` as ``(1280, 800)``."""
    match = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", value)
    if not match or not (16 <= int(match[1]) <= 8192 and 16 <= int(match[2]) <= 8192):
        raise UsageError(f"--png-size takes WIDTHxHEIGHT in pixels, 16 to 8192 each, got {value!r}")
    return int(match[1]), int(match[2])


@click.command("view", cls=GuardedCommand, context_settings=HELP)
@click.argument("robot", type=click.Path())
@click.option(
    "-o",
    "--output",
    required=True,
    type=click.Path(dir_okay=False),
    help="The HTML file to write (atomically); required: the command's whole product is a file.",
)
@click.option(
    "--png",
    type=click.Path(dir_okay=False),
    default=None,
    help="Also write a picture of the page, rendered by a headless Chromium "
    "(or $INERTIA_KIT_CHROMIUM).",
)
@click.option(
    "--png-size",
    default="1280x800",
    show_default=True,
    metavar="WxH",
    help="The picture's size in pixels.",
)
@click.option(
    "--triangle-budget",
    type=click.IntRange(min=1),
    default=DEFAULT_BUDGET,
    show_default=True,
    metavar="N",
    help="Most mesh triangles drawn in the whole page: meshes over it are decimated for display "
    "only (mass properties use the originals).",
)
@click.option("--select", multiple=True, metavar="CODES", help="Rules to run, as inertia-lint.")
@click.option("--ignore", multiple=True, metavar="CODES", help="Rules not to run, as inertia-lint.")
@click.option(
    "--engine",
    "engines",
    multiple=True,
    metavar="NAMES",
    help="Simulators whose view of each link to add to the findings, as inertia-lint.",
)
@click.option(
    "--config",
    "config_path",
    type=click.Path(dir_okay=False),
    default=None,
    help="Configuration file (pyproject.toml or .inertia-kit.toml) instead of the nearest one.",
)
@package_path_option
@xacro_arg_option
@xacro_limit_option
@redact_env_option
@follow_symlinks_option("the page (-o) and the picture (--png)")
@click.pass_context
def view_command(ctx: click.Context, robot: str, **options: Any) -> None:
    """
    Write a review page of ROBOT (a URDF or xacro file): every link's visual geometry, the
    equivalent box of its declared inertia (orange, with the COM) and of the inertia its geometry
    implies (cyan, dashed, with the centroid), links with errors in red, and a side panel with
    each link's declared and geometry values side by side in the link's axes (mass, COM, ixx to
    iyz, principal moments along their axes; the cells that differ highlighted), its implied
    density and findings. Hover or click a box for its link's name; isolate a link, show all.
    One HTML file that works offline: three.js, the meshes and the findings are inside it.

    \b
    It is a viewer: findings do not fail it (inertia-lint is the check).
    Exit codes: 0 the page (and the PNG) written; 2 unreadable input, bad configuration or
    usage, or no renderer for --png (the page is still written).
    \b
    Examples:
      inertia-kit view urdf/robot.urdf.xacro -o review.html
      inertia-kit view robot.urdf -o review.html --png review.png --png-size 1600x1000
    """
    ctx.exit(view(robot, **options))


def view(
    robot: str,
    *,
    output: str,
    png: str | None = None,
    png_size: str = "1280x800",
    triangle_budget: int = DEFAULT_BUDGET,
    select: tuple[str, ...] = (),
    ignore: tuple[str, ...] = (),
    engines: tuple[str, ...] = (),
    config_path: str | None = None,
    package_paths: tuple[str, ...] = (),
    xacro_args: tuple[str, ...] = (),
    xacro_limits: tuple[str, ...] = (),
    redact_env: bool | None = None,
    follow_symlinks: bool = False,
) -> int:
    """``inertia-kit view``: write the page (and the PNG); return the exit code."""
    from inertia_kit.description.edits import write_atomic
    from inertia_kit.description.output_paths import refuse_links
    from inertia_kit.errors import InertiaKitError
    from inertia_kit.view.page import render_page
    from inertia_kit.view.scene import build_scene

    for option, path in (("-o", output), ("--png", png)):
        try:
            if path is not None:
                refuse_links(path, follow_symlinks)
        except InertiaKitError as error:
            say(f"error: {option}: {error}")
            return 2
    try:
        size = _size(png_size) if png else None
        rules = {"select": parse_codes(select)} if select else {}
        if ignore:
            rules["ignore"] = parse_codes(ignore)
        scene = build_scene(
            robot,
            package_paths=package_paths,
            xacro_args=parse_xacro_args(xacro_args),
            config=config_path,
            engines=engines or None,
            xacro_limits=parse_xacro_limits(xacro_limits),
            triangle_budget=triangle_budget,
            redact_environment=redact_env,
            **rules,
        )
        page = render_page(scene).encode("utf-8")
        write_atomic(output, page, create=True, follow_symlinks=follow_symlinks)
    except UsageError as error:
        say(f"error: {error.format_message()}")
        return 2
    except InertiaKitError as error:  # unreadable input, configuration, a file we cannot write
        _keep_out_of_error(error, robot, config_path, redact_env)
        say(f"error: {error}")
        return 2
    findings = sum(len(link["findings"]) for link in scene["links"])
    findings += len(scene.get("findings_elsewhere", ()))
    megabytes = len(page) / 1e6
    links = len(scene["links"])
    say(
        f"wrote {output}: {links} link{'' if links == 1 else 's'}, {findings} "
        f"finding{'' if findings == 1 else 's'}, {megabytes:.1f} MB"
    )
    if png and size:
        from inertia_kit.view.screenshot import RendererError, screenshot

        try:
            screenshot(output, png, width=size[0], height=size[1], follow_symlinks=follow_symlinks)
        except (RendererError, InertiaKitError) as error:
            say(f"error: --png: {error} (the page {output} is written)")
            return 2
        say(f"wrote {png}: {size[0]}x{size[1]} pixels")
    return 0


def _keep_out_of_error(
    error: Exception, robot: str, config: str | None, option: bool | None
) -> None:
    """What the environment gave a xacro expansion that failed, kept out of its message."""
    from inertia_kit.errors import ConfigError
    from inertia_kit.lint.config_files import ConfigFinder

    values = getattr(error, "environment_values", ())
    if not values:
        return
    try:
        configured = ConfigFinder(config).for_file(robot).redact_environment
    except ConfigError:
        configured = False
    if redacting(option, configured):
        keep_out(values)
