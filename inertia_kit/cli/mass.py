"""``inertia-kit mass``: one sub-command per primitive, and ``mesh``; the report is report.mass."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import click

from inertia_kit.cli.guard import GuardedCommand, GuardedGroup, processing
from inertia_kit.cli.options import NUMBER, SCALE, UsageError
from inertia_kit.cli.printing import say
from inertia_kit.fill.materials import MATERIALS, canonical_material, materials_text


@click.group("mass", cls=GuardedGroup)
def mass_group() -> None:
    """
    Mass properties of a primitive or a mesh: mass, centre of mass, the inertia tensor about
    the centre of mass (and about any point), and a ready-to-paste URDF <inertial> block.

    \b
    Examples:
      inertia-kit mass cylinder --radius 0.35 --length 0.4 --density 1024 --about 0 0 -0.2
      inertia-kit mass mesh part.stl --density 2700 --scale 0.001
    """


def _triple(flag: str, help: str, default: tuple[float, float, float] | None) -> Callable:
    return click.option(flag, nargs=3, type=NUMBER, default=default, help=help)


# how much the part weighs, where it is placed, and about what it is reported: every sub-command
_ORIGIN = (0.0, 0.0, 0.0)
_PART_OPTIONS = (
    click.option(
        "--density",
        type=SCALE,
        default=None,
        help="Uniform density, kg/m³ (default 1000 unless --mass is given).",
    ),
    click.option(
        "--material",
        default=None,
        metavar="NAME",
        help=f"Density from a material (any case; aluminum, stainless_steel too): "
        f"{materials_text()}.",
    ),
    click.option("--mass", "mass_kg", type=SCALE, default=None, help="Total mass, kg."),
    _triple(
        "--xyz",
        "Place the shape: its origin in the link frame, m (as a URDF <origin xyz>).",
        _ORIGIN,
    ),
    _triple("--rpy", "Place the shape: roll pitch yaw, rad (as a URDF <origin rpy>).", _ORIGIN),
    _triple("--about", "Also report the tensor about this point of the link frame, m.", None),
    _triple(
        "--about-rpy", "...and in the axes of a frame rotated by these roll pitch yaw, rad.", None
    ),
    click.option(
        "--format",
        "output_format",
        type=click.Choice(["text", "json"]),
        default="text",
        show_default=True,
    ),
)

_RADIUS = ("--radius", 1, "m")
# shape -> (help, its dimensions: option, how many numbers, help), in the order
# ``inertia_kit.physics.primitives.<shape>`` takes them
_PRIMITIVES: dict[str, tuple[str, tuple[tuple[str, int, str], ...]]] = {
    "box": ("A solid box centred on its frame.", (("--size", 3, "Edge lengths x y z, m."),)),
    "cylinder": (
        "A solid cylinder along z, centred on its frame (as URDF).",
        (_RADIUS, ("--length", 1, "m, along z")),
    ),
    "sphere": ("A solid sphere.", (_RADIUS,)),
    "capsule": (
        "A solid capsule along z: a cylinder capped by two hemispheres.",
        (_RADIUS, ("--length", 1, "m, of the cylinder between the caps")),
    ),
    "ellipsoid": (
        "A solid ellipsoid with semi-axes along x, y, z.",
        (("--radii", 3, "Semi-axes a b c, m."),),
    ),
}


def _with_options(command: Callable, options: list[Callable]) -> Callable:
    """``command`` decorated with ``options``, shown in this order by ``--help``."""
    for option in reversed(options):
        command = option(command)
    return command


def _part_options(command: Callable) -> Callable:
    """The options every sub-command takes after its own."""
    return _with_options(command, list(_PART_OPTIONS))


def _primitive_command(shape: str, help: str, dimensions: tuple) -> click.Command:
    names = [flag.lstrip("-") for flag, _, _ in dimensions]

    def run(**options: Any) -> None:
        from inertia_kit.physics import primitives
        from inertia_kit.report.mass import Part

        sizes = [options.pop(name) for name in names]
        description: dict[str, Any] = {"shape": shape}
        for name, size in zip(names, sizes, strict=True):
            description[name] = list(size) if isinstance(size, tuple) else size
        try:
            # at unit density the mass is the volume
            part = Part(description, getattr(primitives, shape)(*sizes, density=1.0))
        except ValueError as error:
            raise UsageError(str(error)) from None
        _show(part, options)

    own = [
        click.option(flag, nargs=n, type=NUMBER, required=True, help=text)
        for flag, n, text in dimensions
    ]
    return click.command(shape, cls=GuardedCommand, help=help)(
        _with_options(_part_options(run), own)
    )


for _shape, (_help, _dimensions) in _PRIMITIVES.items():
    mass_group.add_command(_primitive_command(_shape, _help, _dimensions))


@mass_group.command("mesh")
@click.argument("path", type=click.Path(dir_okay=False))
@click.option(
    "--scale",
    default=None,
    help='URDF mesh scale: one factor or three, e.g. 0.001 or "0.001 0.001 0.001" [default: 1].',
)
@click.option(
    "--trust-units",
    is_flag=True,
    help="The mesh is in metres: print its URDF block even when its size looks like mm, cm "
    "or inches (without --scale, such a mesh gets a warning and no block).",
)
@_part_options
def mass_mesh(path: str, scale: str | None, trust_units: bool, **options: Any) -> None:
    """A closed triangle mesh: STL, OBJ, DAE, PLY or GLB."""
    factors = _parse_scale(scale or "1")
    from inertia_kit.errors import MeshError
    from inertia_kit.report.mass import mesh_part

    with processing(path):
        try:
            part = mesh_part(path, factors)
        except MeshError as error:
            raise UsageError(str(error)) from None
        warning = _unit_warning(path, part, options.get("mass_kg"))
        withheld = None
        if warning is not None:
            say(f"warning: {warning}")
            if scale is None and not trust_units:
                withheld = "the mesh looks authored in other units than metres (see the warning)"
        _show(part, {**options, "withheld": withheld})


def _unit_warning(path: str, part: Any, mass_kg: float | None) -> str | None:
    """
    What the mesh's size (and density, when ``--mass`` is given) says of its unit, when it
    looks authored in mm, cm or inches (analysis.mesh_units decides, as IN031 does), or None.
    A lone mesh has no joints or peers: its size alone is evidence enough.
    """
    from inertia_kit.analysis.mesh_units import (
        SLIPS,
        VIOLATION,
        density_evidence,
        size_evidence,
        suspected_unit,
    )
    from inertia_kit.physics.formatting import fmt

    low, high = part.mesh["bounds"]
    extent = max(h - lo for lo, h in zip(low, high, strict=True))
    if not extent > 0:
        return None
    evidence = [size_evidence(extent)]
    if mass_kg is not None:
        evidence.append(density_evidence(mass_kg, part.volume))
    suspicion = suspected_unit(evidence, min_evidence=1)
    if suspicion.slip is None:
        return None
    slip = suspicion.slip
    scale = [fmt(v * slip, 6) for v in part.description["scale"]]
    scale_text = scale[0] if len(set(scale)) == 1 else f'"{" ".join(scale)}"'
    against = "; ".join(e.text(0.0) for e in evidence if e.excess() > VIOLATION)
    unit = f"authored in {suspicion.unit}" if suspicion.unit else "scaled twice"
    return (
        f"{path} spans {fmt(extent, 3)} m as scaled: it looks {unit} ({SLIPS[slip]}: "
        f"{against}); pass --scale {scale_text} (it then spans {fmt(extent * slip, 3)} m), "
        "or --trust-units if it really is that size"
    )


def _parse_scale(text: str) -> tuple[float, float, float]:
    from inertia_kit.physics.numbers import usable

    try:
        values = [float(part) for part in text.replace(",", " ").split()]
    except ValueError:
        raise UsageError(f"--scale takes one or three numbers, got {text!r}") from None
    if not all(usable(value) for value in values):
        raise UsageError(f"--scale takes numbers of at most 1e50, not subnormal, got {text!r}")
    if len(values) == 1:
        values *= 3
    if len(values) != 3:
        raise UsageError(f"--scale takes one or three numbers, got {len(values)}")
    if 0 in values:  # a zero factor flattens the mesh: no volume (a negative one mirrors it)
        raise UsageError(f"--scale takes non-zero factors (a negative one mirrors), got {text!r}")
    return values[0], values[1], values[2]


def _material_density(options: dict[str, Any]) -> None:
    """``--material`` turned into ``--density`` in ``options``, or a usage error."""
    material = options.pop("material", None)
    if material is None:
        return
    if options.get("density") is not None:
        raise UsageError("give --density or --material, not both")
    name = canonical_material(material)
    if name is None:
        raise UsageError(
            f"--material: unknown {material!r}; known: {', '.join(MATERIALS)} (in any case, "
            "with spaces or underscores for hyphens; aluminum is aluminium)"
        )
    options["density"] = MATERIALS[name]


def _show(part: Any, options: dict[str, Any]) -> None:
    from inertia_kit.report.mass import render

    _material_density(options)
    try:
        text = render(part, **options)
    except ValueError as error:
        raise UsageError(str(error)) from None
    click.echo(text)
