"""The ``impactmaps`` command line. Every subcommand accepts ``--json``.

Subcommands: chart (the main job), point, asymptote, classify, lookup, sweep,
simulate, fd, halfspace, restitution. ``impactmaps SUBCOMMAND --help`` documents each.
"""

from __future__ import annotations

import argparse
import sys
import warnings
from pathlib import Path

from .jsonio import dumps

__all__ = ["main", "build_parser"]


# -- helpers -------------------------------------------------------------------------------
def _emit(values: dict, as_json: bool, units: dict | None = None) -> None:
    if as_json:
        print(dumps(values))
        return
    units = units or {}
    width = max(len(k) for k in values)
    for key, value in values.items():
        if isinstance(value, float):
            text = f"{value:.6g}"
        else:
            text = str(value)
        print(f"{key:<{width}}  {text}{(' ' + units[key]) if key in units else ''}")


def _material_from_args(args, prefix: str, role: str):
    """Catalogue name or explicit E, ν, ρ (+ yield) for the impactor or the target."""
    from .materials import IsotropicMaterial, material

    name = getattr(args, f"{prefix}material")
    if name is not None:
        chosen = material(name)
        if args.yield_strength is not None and isinstance(chosen, IsotropicMaterial):
            chosen = IsotropicMaterial(chosen.youngs_modulus, chosen.poisson_ratio, chosen.density,
                                       args.yield_strength, chosen.name)
        return chosen
    missing = [flag for flag, value in (("--youngs-modulus", args.youngs_modulus),
                                        ("--poisson-ratio", args.poisson_ratio),
                                        ("--density", args.density)) if value is None]
    if missing:
        raise ValueError(
            f"the {role} material is not given: use --{prefix.replace('_', '-')}material NAME "
            f"or {', '.join(missing)} (explicit values apply to both bodies)"
        )
    return IsotropicMaterial(args.youngs_modulus, args.poisson_ratio, args.density, args.yield_strength)


# -- subcommands -----------------------------------------------------------------------------
def _cmd_restitution(args) -> dict:
    from .solvers.halfspace import restitution

    return {"beta": args.beta, "restitution": float(restitution(args.beta))}


def _cmd_halfspace(args) -> dict:
    from .contact import Sphere, law_for_sphere
    from .solvers.halfspace import halfspace_impact

    impactor_material = _material_from_args(args, "", "impactor")
    target_material = _material_from_args(args, "target_", "target")
    sphere = Sphere(args.radius, impactor_material, args.mass)
    law = law_for_sphere(args.law, sphere, target_material)
    result = halfspace_impact(law, sphere.mass, args.velocity)
    summary = result.summary()
    return {
        "law": args.law,
        "impactor_mass_kg": float(sphere.mass),
        **{key: summary[key] for key in ("peak_force_N", "first_contact_duration_s", "max_indentation_m",
                                         "permanent_indentation_m", "restitution", "energy_loss_J")},
    }


def _structure_from_args(args):
    from .maps.structures import MapStructure

    kind, _, supports = args.target.partition("-")
    if kind not in ("beam", "plate") or not supports:
        raise ValueError(f"--target = {args.target!r} is not known: use beam-SUPPORTS (e.g. beam-ss, beam-cc) "
                         "or plate-EDGES (e.g. plate-ss, plate-ssss, plate-cccc)")
    if kind == "plate" and supports.lower() == "ss":
        supports = "SSSS"
    theory = args.theory or ("euler" if kind == "beam" else "kirchhoff")
    fractions = (args.position,) if kind == "beam" else (args.position, args.position_y)
    return MapStructure(kind=kind, theory=theory, supports=supports, aspect_ratio=args.aspect,
                        slenderness=args.slenderness, impact_fraction=fractions)


def _settings_from_args(args):
    from .solvers.modal import ModalSettings

    options = {} if args.time_step_ratio is None else {"time_step_ratio": args.time_step_ratio}
    return ModalSettings(cutoff_ratio=args.cutoff_ratio, check_convergence=not getattr(args, "no_check", False),
                         **options)


def _cmd_point(args) -> dict:
    from .maps.regimes import classify, infinite_structure_peak, quasi_static_peak
    from .maps.sweep import reflection_time
    from .solvers.modal import simulate_normalised

    structure = _structure_from_args(args)
    target = structure.build()
    result = simulate_normalised(target, args.zeta, args.lambda_, settings=_settings_from_args(args), record=False)
    reflection = float(reflection_time(target, result.contact_frequency))
    regime = str(classify(result.fmax_normalised, args.zeta, args.lambda_, structure.kind,
                          peak_time=result.peak_time_normalised, reflection_time=reflection))
    return {
        "structure": structure.name,
        "zeta": args.zeta,
        "lambda": args.lambda_,
        **result.normalised_summary(),
        "regime": regime,
        "halfspace_fmax": 1.0,
        "quasi_static_fmax": float(quasi_static_peak(args.lambda_)),
        "infinite_structure_fmax": float(infinite_structure_peak(args.zeta, structure.kind)),
        "reflection_time_normalised": reflection,
        "method": result.method,
    }


def _cmd_asymptote(args) -> dict:
    from .solvers import asymptotes

    if args.which == "quasi-static":
        if args.lambda_ is None:
            raise ValueError("--lambda is required for the quasi-static asymptote (valid range (0, inf))")
        return {
            "asymptote": args.which,
            "lambda": args.lambda_,
            "fmax_normalised": float(asymptotes.quasi_static_peak(args.lambda_)),
            "contact_time_normalised": float(asymptotes.quasi_static_contact_time(args.lambda_)),
            "impacts": 1,
        }
    if args.zeta is None:
        raise ValueError(f"--zeta is required for the {args.which} asymptote (valid range (0, inf))")
    if args.which == "infinite-plate":
        peak, contact = asymptotes.infinite_plate_peak(args.zeta), asymptotes.infinite_plate_contact_time(args.zeta)
    else:
        peak, contact = asymptotes.infinite_beam_peak(args.zeta), asymptotes.infinite_beam_contact_time(args.zeta)
    return {
        "asymptote": args.which,
        "zeta": args.zeta,
        "fmax_normalised": float(peak),
        "contact_time_normalised": float(contact),
        "impacts": 1,
    }


def _cmd_classify(args) -> dict:
    if args.from_map:
        from .maps.lookup import lookup

        theory = "euler" if args.structure == "beam" else "kirchhoff"
        found = lookup(args.zeta, args.lambda_, structure=args.structure, theory=theory,
                       tolerance=args.tolerance)
        return {"regime": found.regime, "fmax_normalised": found.fmax_normalised, "source": f"map {found.map_name}"}
    args.target = "beam-ss" if args.structure == "beam" else "plate-ss"
    args.theory = None
    point = _cmd_point(args)
    return {"regime": point["regime"], "fmax_normalised": point["fmax_normalised"],
            "source": f"simulation {point['structure']}"}


def _cmd_lookup(args) -> dict:
    from .maps.lookup import lookup

    if args.case is not None:
        from .cases import case_dimensionless, load_case

        case = load_case(args.case)
        numbers = case_dimensionless(case)
        found = lookup(numbers["zeta"], numbers["lambda"], structure=args.structure, theory=args.theory)
        return {
            "fmax_normalised": found.fmax_normalised,
            "regime": found.regime,
            "zeta": numbers["zeta"],
            "lambda": numbers["lambda"],
            "peak_force_N": float(found.peak_force(numbers["impactor_mass_kg"], numbers["velocity_m_s"],
                                                   numbers["contact_stiffness_N_m"])),
            "map": found.map_name,
        }
    if args.zeta is None or args.lambda_ is None:
        raise ValueError("give --zeta and --lambda, or --case CASE.toml")
    found = lookup(args.zeta, args.lambda_, structure=args.structure, theory=args.theory)
    return {"fmax_normalised": found.fmax_normalised, "regime": found.regime, "map": found.map_name}


def _cmd_chart(args) -> dict:
    from .maps.chart import make_chart

    paths = make_chart(out_dir=Path(args.out), zeta_range=tuple(args.zeta_range), zeta_count=args.zeta_count,
                       lambdas=args.lambdas, progress=not args.quiet, max_workers=args.workers)
    return {key: str(value) for key, value in paths.items()}


def _cmd_sweep(args) -> dict:
    from .maps.config import run_sweep_config

    paths = run_sweep_config(args.config, progress=not args.quiet)
    return {key: str(value) for key, value in paths.items()}


def _cmd_simulate(args) -> dict:
    from .cases import load_case, run_case, write_case_outputs

    case = load_case(args.case)
    result, summary = run_case(case)
    paths = write_case_outputs(case, result, Path(args.out))
    summary = dict(summary)
    summary["outputs"] = {key: str(value) for key, value in paths.items()}
    return summary


def _cmd_fd(args) -> dict:
    from .cases import load_case, run_case

    case = load_case(args.case, solver="fd")
    _, summary = run_case(case)
    return summary


# -- parser ------------------------------------------------------------------------------------
def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="impactmaps", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)

    def add(name, help_text, handler):
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--json", action="store_true", help="print one JSON object")
        p.set_defaults(handler=handler)
        return p

    p = add("chart", "the normalised max-force chart (Figure 2), its data and lookup table", _cmd_chart)
    p.add_argument("--out", default="impactmaps-output", help="output directory (default ./impactmaps-output)")
    p.add_argument("--zeta-range", nargs=2, type=float, default=(0.005, 100.0), metavar=("A", "B"))
    p.add_argument("--zeta-count", type=int, default=60)
    p.add_argument("--lambdas", nargs="+", type=float, default=None, help="λ values (default 0.05 … 20, 8 values)")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all cores)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")

    p = add("point", "simulate one (ζ, λ) point on a beam or plate", _cmd_point)
    _point_arguments(p)

    p = add("asymptote", "closed-form asymptote: infinite beam, infinite plate or quasi-static", _cmd_asymptote)
    p.add_argument("which", choices=("infinite-beam", "infinite-plate", "quasi-static"))
    p.add_argument("--zeta", type=float)
    p.add_argument("--lambda", dest="lambda_", type=float)

    p = add("classify", "regime of an impact at (ζ, λ)", _cmd_classify)
    p.add_argument("--zeta", type=float, required=True)
    p.add_argument("--lambda", dest="lambda_", type=float, required=True)
    p.add_argument("--structure", choices=("beam", "plate"), required=True)
    p.add_argument("--tolerance", type=float, default=0.1)
    p.add_argument("--from-map", action="store_true", help="interpolate the shipped map instead of simulating")
    _point_arguments(p, with_target=False)

    p = add("lookup", "F̄max and regime from the shipped maps (no simulation)", _cmd_lookup)
    p.add_argument("--structure", choices=("beam", "plate"), required=True)
    p.add_argument("--theory", choices=("euler", "timoshenko", "kirchhoff", "mindlin"), required=True)
    p.add_argument("--zeta", type=float)
    p.add_argument("--lambda", dest="lambda_", type=float)
    p.add_argument("--case", type=Path, help="a physical case file: gives the peak force in newtons too")

    p = add("sweep", "run a sweep described by a TOML file", _cmd_sweep)
    p.add_argument("config", type=Path)
    p.add_argument("--quiet", action="store_true")

    p = add("simulate", "simulate a physical case file (TOML) with the modal solver", _cmd_simulate)
    p.add_argument("case", type=Path)
    p.add_argument("--out", default="impactmaps-output", help="directory for the CSV histories and summary.json")

    p = add("fd", "simulate a beam case file with the finite-difference elastic-plastic solver", _cmd_fd)
    p.add_argument("case", type=Path)

    p = add("halfspace", "sphere on a half-space with any contact law", _cmd_halfspace)
    p.add_argument("--law", required=True)
    p.add_argument("--radius", type=float, required=True, help="sphere radius [m]")
    p.add_argument("--velocity", type=float, required=True, help="impact velocity [m/s]")
    p.add_argument("--mass", type=float, default=None, help="impactor mass [kg] (default: the solid sphere's)")
    p.add_argument("--material", default=None, help="impactor catalogue material")
    p.add_argument("--target-material", default=None, help="target catalogue material")
    p.add_argument("--youngs-modulus", type=float, default=None, help="E [Pa] of both bodies")
    p.add_argument("--poisson-ratio", type=float, default=None, help="ν of both bodies")
    p.add_argument("--density", type=float, default=None, help="ρ [kg/m³] of both bodies")
    p.add_argument("--yield-strength", type=float, default=None, help="yield strength [Pa] (plastic laws)")

    p = add("restitution", "coefficient of restitution e(β) of the Yigit–Christoforou law", _cmd_restitution)
    p.add_argument("--beta", type=float, required=True, help="impact number β")
    return parser


def _point_arguments(p, with_target=True):
    if with_target:
        p.add_argument("--target", required=True, help="beam-ss, beam-cc, beam-cs, beam-cf, beam-ff, plate-ss, …")
        p.add_argument("--theory", default=None, help="euler|rayleigh|timoshenko or kirchhoff|mindlin")
        p.add_argument("--zeta", type=float, required=True)
        p.add_argument("--lambda", dest="lambda_", type=float, required=True)
    p.add_argument("--aspect", type=float, default=1.0, help="plate aspect ratio b/a")
    p.add_argument("--slenderness", type=float, default=20.0, help="span/thickness")
    p.add_argument("--position", type=float, default=0.5, help="impact point x0/L (or x0/a)")
    p.add_argument("--position-y", type=float, default=0.5, help="impact point y0/b (plates)")
    p.add_argument("--cutoff-ratio", type=float, default=40.0, help="mode cut-off / contact frequency")
    p.add_argument("--time-step-ratio", type=float, default=None,
                   help="upper bound of ω Δt (default: the solver's, ModalSettings)")
    p.add_argument("--no-check", action="store_true", help="skip the convergence re-run")


def main(argv=None) -> int:
    """Entry point of the ``impactmaps`` command; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            values = args.handler(args)
        for warning in caught:
            print(f"warning: {warning.message}", file=sys.stderr)
    except (ValueError, FileNotFoundError) as error:
        if args.json:
            print(dumps({"error": str(error)}))
        print(f"impactmaps {args.command}: error: {error}", file=sys.stderr)
        return 2
    _emit(values, args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
