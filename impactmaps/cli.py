"""The ``impactmaps`` command line. Every subcommand accepts ``--json``.

Subcommands: chart (the main job), point, asymptote, classify, lookup, sweep,
simulate, fd, halfspace, restitution, materials, laws. ``impactmaps SUBCOMMAND --help``
documents each. Bad input exits with status 2 and one line naming the option as typed,
its value and the valid range; Ctrl-C exits with status 130 (a sweep saves its points
first). With ``--json`` the output is strict JSON: a quantity that does not exist
(NaN, inf) is ``null`` and a companion ``…_note`` key says why.
"""

from __future__ import annotations

import argparse
import math
import sys
import warnings
from pathlib import Path

from .jsonio import dumps

__all__ = ["main", "build_parser"]

#: Largest β for which the closed form of e(β) keeps ~9 significant digits.
MAX_RESTITUTION_BETA = 1e8
#: Seconds to wait for a Dask scheduler (``sweep --scheduler``).
SCHEDULER_TIMEOUT_S = 5.0


# -- helpers -------------------------------------------------------------------------------
def _emit(values: dict, as_json: bool, indent: str = "") -> None:
    if as_json:
        print(dumps(values))
        return
    width = max((len(str(k)) for k in values), default=0)
    for key, value in values.items():
        if isinstance(value, dict):
            print(f"{indent}{key}")
            _emit(value, False, indent + "  ")
            continue
        text = f"{value:.6g}" if isinstance(value, float) else ("-" if value is None else str(value))
        print(f"{indent}{key:<{width}}  {text}")


def _check(option: str, value, low: float = 0.0, high: float = math.inf, what: str = "",
           low_inclusive: bool = False, high_inclusive: bool = False, note: str = "") -> None:
    """Refuse ``value`` of the command-line ``option`` outside its range (NaN too); ``None`` passes."""
    if value is None:
        return
    above = value >= low if low_inclusive else value > low
    below = value <= high if high_inclusive else value < high
    if not (above and below):
        interval = f"{'[' if low_inclusive else '('}{low:g}, {high:g}{']' if high_inclusive else ')'}"
        raise ValueError(f"{option} = {value:g} is invalid: {what + ' ' if what else 'it '}must be in {interval}"
                         f"{'; ' + note if note else ''}")


def _refuse(args, options: dict, reason: str) -> None:
    """Refuse the options (``{"--flag": attribute}``) that were given but would be ignored."""
    given = [flag for flag, attribute in options.items() if getattr(args, attribute, None) not in (None, False)]
    if given:
        raise ValueError(f"{', '.join(given)} cannot be used {reason}")


def _out_dir(option: str, value) -> Path:
    out = Path(value)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{option} = {str(out)!r} is a file, not a directory")
    return out


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


def _converged(caught) -> bool:
    """False if the convergence re-run warned that the result moved."""
    from .solvers.modal import ConvergenceWarning

    return not any(issubclass(w.category, ConvergenceWarning) and "not converged" in str(w.message) for w in caught)


def _run_checked(function, *args, **kwargs):
    """Call ``function``; return (its value, converged flag); warnings are passed on."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        value = function(*args, **kwargs)
    for warning in caught:
        warnings.warn_explicit(warning.message, warning.category, warning.filename, warning.lineno)
    return value, _converged(caught)


def _save_figure(result, path: Path, normalised: bool) -> str:
    from .plotting import save_impact_history

    if path.exists() and path.is_dir():
        raise ValueError(f"--plot = {str(path)!r} is a directory: give an image file name (e.g. history.png)")
    save_impact_history(result, path, normalised=normalised)
    return str(path)


# -- subcommands -----------------------------------------------------------------------------
def _cmd_restitution(args) -> dict:
    from .solvers.halfspace import restitution

    _check("--beta", args.beta, 0.0, MAX_RESTITUTION_BETA, "the impact number β", high_inclusive=True,
           note="beyond it the closed form loses accuracy")
    return {"beta": args.beta, "restitution": float(restitution(args.beta))}


def _cmd_halfspace(args) -> dict:
    from .contact import Sphere, law_for_sphere
    from .solvers.halfspace import halfspace_impact

    if args.material is not None and args.target_material is not None:
        _refuse(args, {"--youngs-modulus": "youngs_modulus", "--poisson-ratio": "poisson_ratio",
                       "--density": "density"},
                "with both --material and --target-material (explicit values stand for a body without a name)")
    _check("--radius", args.radius, what="the sphere radius [m]")
    _check("--velocity", args.velocity, what="the impact velocity [m/s]")
    _check("--mass", args.mass, what="the impactor mass [kg]")
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


def _point_defaults(args) -> None:
    """Check the point options as typed, then fill in their defaults."""
    _check("--zeta", args.zeta, what="the loss factor ζ")
    _check("--lambda", args.lambda_, what="the relative stiffness λ")
    _check("--aspect", args.aspect, what="the plate aspect ratio b/a")
    _check("--slenderness", args.slenderness, 2.0, what="span/thickness", low_inclusive=True)
    _check("--position", args.position, 0.0, 1.0, "the impact point x0/L")
    _check("--position-y", args.position_y, 0.0, 1.0, "the impact point y0/b")
    _check("--cutoff-ratio", args.cutoff_ratio, what="the mode cut-off / contact frequency")
    _check("--time-step-ratio", args.time_step_ratio, what="the bound of ω Δt")
    for name, default in (("aspect", 1.0), ("slenderness", 20.0), ("position", 0.5), ("position_y", 0.5),
                          ("cutoff_ratio", 40.0)):
        if getattr(args, name) is None:
            setattr(args, name, default)


def _structure_from_args(args):
    from .maps.structures import MapStructure
    from .targets.options import STRUCTURE_KINDS

    kind, _, supports = args.target.partition("-")
    if kind not in STRUCTURE_KINDS or not supports:
        raise ValueError(f"--target = {args.target!r} is not known: use beam-SUPPORTS (e.g. beam-ss, beam-cc) "
                         "or plate-EDGES (e.g. plate-ss, plate-ssss, plate-cccc)")
    if kind == "beam":
        _refuse(args, {"--aspect": "aspect", "--position-y": "position_y"}, "with a beam --target")
    if kind == "plate" and supports.lower() == "ss":
        supports = "SSSS"
    _point_defaults(args)
    theory = args.theory or ("euler" if kind == "beam" else "kirchhoff")
    fractions = (args.position,) if kind == "beam" else (args.position, args.position_y)
    try:
        structure = MapStructure(kind=kind, theory=theory, supports=supports, aspect_ratio=args.aspect,
                                 slenderness=args.slenderness, impact_fraction=fractions)
        structure.build()
    except ValueError as error:
        raise ValueError(f"--target {args.target} --theory {theory}: {error}") from None
    return structure


def _settings_from_args(args):
    from .solvers.modal import ModalSettings

    options = {} if args.time_step_ratio is None else {"time_step_ratio": args.time_step_ratio}
    return ModalSettings(cutoff_ratio=args.cutoff_ratio, check_convergence=not getattr(args, "no_check", False),
                         **options)


def _cmd_point(args) -> dict:
    from .maps.regimes import classify, infinite_structure_peak, quasi_static_peak
    from .solvers.modal import simulate_normalised

    structure = _structure_from_args(args)
    target = structure.build()
    settings = _settings_from_args(args)
    plot = getattr(args, "plot", None)
    result, converged = _run_checked(simulate_normalised, target, args.zeta, args.lambda_, settings=settings,
                                     record=plot is not None)
    reflection = float(target.reflection_time(result.contact_frequency))
    regime = str(classify(result.fmax_normalised, args.zeta, args.lambda_, structure.kind,
                          peak_time=result.peak_time_normalised, reflection_time=reflection,
                          tolerance=getattr(args, "tolerance", 0.1)))
    values = {
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
        "converged": converged if settings.check_convergence else None,
    }
    if not math.isfinite(reflection):
        values["reflection_time_note"] = "no support or edge reflects waves back to the impact point"
    if not settings.check_convergence:
        values["converged_note"] = "not checked (--no-check)"
    if plot is not None:
        values["plot"] = _save_figure(result, Path(plot), normalised=True)
    return values


def _cmd_asymptote(args) -> dict:
    from .solvers import asymptotes

    if args.which == "quasi-static":
        _refuse(args, {"--zeta": "zeta"}, "with the quasi-static asymptote (it depends on λ only)")
        if args.lambda_ is None:
            raise ValueError("--lambda is required for the quasi-static asymptote (valid range (0, inf))")
        _check("--lambda", args.lambda_, what="the relative stiffness λ")
        return {
            "asymptote": args.which,
            "lambda": args.lambda_,
            "fmax_normalised": float(asymptotes.quasi_static_peak(args.lambda_)),
            "contact_time_normalised": float(asymptotes.quasi_static_contact_time(args.lambda_)),
            "impacts": 1,
        }
    _refuse(args, {"--lambda": "lambda_"}, f"with the {args.which} asymptote (it depends on ζ only)")
    if args.zeta is None:
        raise ValueError(f"--zeta is required for the {args.which} asymptote (valid range (0, inf))")
    _check("--zeta", args.zeta, what="the loss factor ζ")
    if args.which == "infinite-plate":
        peak, contact = asymptotes.infinite_plate_peak(args.zeta), asymptotes.infinite_plate_contact_time(args.zeta)
    else:
        peak, contact = asymptotes.infinite_beam_peak(args.zeta), asymptotes.infinite_beam_contact_time(args.zeta)
    values = {"asymptote": args.which, "zeta": args.zeta, "fmax_normalised": float(peak),
              "contact_time_normalised": float(contact), "impacts": 1}
    if not math.isfinite(float(contact)):
        values["contact_time_note"] = "the sphere never separates from the infinite structure at this ζ"
    if args.which == "infinite-beam":
        values.update(_beam_impacts(args.zeta))
    return values


def _beam_impacts(zeta: float) -> dict:
    """How often the infinite beam is struck: once, or again after the first separation."""
    from .solvers.infinite_beam import critical_beam_loss_factor, recontact_beam_loss_factor

    recontact, critical = recontact_beam_loss_factor(), critical_beam_loss_factor()
    if recontact < zeta < critical:
        return {"impacts": None, "repeated_impacts": True,
                "impacts_note": f"{recontact:.6g} < ζ < {critical:.6g}: the sphere still moves towards the beam "
                                "when it first separates and strikes again (at least 2 impacts; the later "
                                "ones: impactmaps.solvers.infinite_beam.infinite_beam_force); "
                                "contact_time_normalised is the first contact's"}
    return {"impacts": 1, "repeated_impacts": False}


def _cmd_classify(args) -> dict:
    _check("--tolerance", args.tolerance, 0.0, 1.0, "the relative distance to an asymptote",
           high_inclusive=True)
    if args.from_map:
        from .maps.lookup import lookup

        _refuse(args, {"--aspect": "aspect", "--slenderness": "slenderness", "--position": "position",
                       "--position-y": "position_y", "--cutoff-ratio": "cutoff_ratio",
                       "--time-step-ratio": "time_step_ratio", "--no-check": "no_check"},
                "with --from-map (the shipped maps are for centre impacts on SS beams and square plates)")
        _check("--zeta", args.zeta, what="the loss factor ζ")
        _check("--lambda", args.lambda_, what="the relative stiffness λ")
        theory = "euler" if args.structure == "beam" else "kirchhoff"
        found = lookup(args.zeta, args.lambda_, structure=args.structure, theory=theory,
                       tolerance=args.tolerance)
        return {"regime": found.regime, "fmax_normalised": found.fmax_normalised, "source": f"map {found.map_name}"}
    args.target = "beam-ss" if args.structure == "beam" else "plate-ss"
    args.theory = None
    point = _cmd_point(args)
    return {"regime": point["regime"], "fmax_normalised": point["fmax_normalised"],
            "source": f"simulation {point['structure']}", "converged": point["converged"]}


def _cmd_lookup(args) -> dict:
    from .maps.lookup import lookup

    if args.case is not None:
        from .cases import case_dimensionless, load_case

        _refuse(args, {"--zeta": "zeta", "--lambda": "lambda_"}, "with --case (the case gives ζ and λ)")
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
    _check("--zeta", args.zeta, what="the loss factor ζ")
    _check("--lambda", args.lambda_, what="the relative stiffness λ")
    found = lookup(args.zeta, args.lambda_, structure=args.structure, theory=args.theory)
    return {"fmax_normalised": found.fmax_normalised, "regime": found.regime, "map": found.map_name}


def _cmd_chart(args) -> dict:
    from .maps.chart import check_chart_grid, make_chart

    _check("--workers", args.workers, 1.0, math.inf, "the number of worker processes",
           low_inclusive=True)
    check_chart_grid(args.zeta_range, args.zeta_count, args.lambdas)
    paths = make_chart(out_dir=_out_dir("--out", args.out), zeta_range=tuple(args.zeta_range),
                       zeta_count=args.zeta_count, lambdas=args.lambdas, progress=not args.quiet,
                       max_workers=args.workers, overwrite=args.overwrite)
    return {key: str(value) for key, value in paths.items()}


def _cmd_sweep(args) -> dict:
    from .maps.config import run_sweep_config

    _check("--workers", args.workers, 1.0, math.inf, "the number of worker processes",
           low_inclusive=True)
    if args.scheduler is None:
        paths = run_sweep_config(args.config, progress=not args.quiet, overwrite=args.overwrite,
                                 max_workers=args.workers)
        return {key: str(value) for key, value in paths.items()}
    _refuse(args, {"--workers": "workers"}, "with --scheduler (the cluster has its own workers)")
    try:
        from dask.distributed import Client
    except ImportError:
        raise ValueError("--scheduler needs dask.distributed: pip install 'impactmaps[dask]'") from None
    try:
        client = Client(args.scheduler, timeout=SCHEDULER_TIMEOUT_S)
    except (OSError, TimeoutError) as error:
        raise ValueError(f"--scheduler = {args.scheduler!r} cannot be reached: {error}") from None
    with client:
        paths = run_sweep_config(args.config, progress=not args.quiet, overwrite=args.overwrite,
                                 executor=client.get_executor())
    return {key: str(value) for key, value in paths.items()} | {"scheduler": args.scheduler}


def _run_case_command(args, solver) -> dict:
    from .cases import load_case, run_case, write_case_outputs

    out = _out_dir("--out", args.out)
    case = load_case(args.case, solver=solver)
    (result, summary), converged = _run_checked(run_case, case)
    paths = write_case_outputs(case, result, out)
    paths["figure"] = out / "history.png"
    _save_figure(result, paths["figure"], normalised=False)
    summary = dict(summary)
    summary["converged"] = converged if case.settings is not None and case.settings.check_convergence else None
    summary["outputs"] = {key: str(value) for key, value in paths.items()}
    return summary


def _cmd_simulate(args) -> dict:
    return _run_case_command(args, None)


def _cmd_fd(args) -> dict:
    return _run_case_command(args, "fd")


def _cmd_materials(args) -> dict:
    from dataclasses import fields

    from .materials import CATALOGUE, material

    sources = _catalogue_sources(material.__doc__ or "")
    out = {}
    for name, entry in sorted(CATALOGUE.items()):
        values = {"kind": type(entry).__name__}
        values |= {f.name: getattr(entry, f.name) for f in fields(entry) if f.init and not f.name.startswith("_")}
        out[name] = values | {"source": sources.get(name)}
    return {"materials": out, "units": "SI: moduli and strengths [Pa], density [kg/m³]",
            "sources_note": "full citations beside each entry of impactmaps.materials.CATALOGUE"}


def _catalogue_sources(doc: str) -> dict:
    """``{name: source}`` from the bullets ``* ``name`` — source`` of a docstring."""
    import re

    text = " ".join(line.strip() for line in doc.splitlines())
    found = re.findall(r"\* ``([\w-]+)`` — (.*?)(?=\* ``|Raises|$)", text)
    return {name: source.strip().rstrip(";.").replace("**", "") for name, source in found}


def _cmd_laws(args) -> dict:
    import inspect

    from .contact import available_contact_laws, contact_law_class

    out = {}
    for name in available_contact_laws():
        cls = contact_law_class(name)
        module = sys.modules[cls.__module__]
        options = {p.name: (None if p.default is inspect.Parameter.empty else p.default)
                   for p in inspect.signature(cls).parameters.values()}
        out[name] = {"class": f"{cls.__module__}.{cls.__name__}",
                     "description": (module.__doc__ or cls.__doc__ or "").strip().splitlines()[0],
                     "options": options}
    return {"laws": out, "options_note": "null: required (SI units); case files build them from the materials"}


# -- parser ------------------------------------------------------------------------------------
class _UsageError(Exception):
    """A command line argparse cannot parse (reported by :func:`main` as one line, exit 2)."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):
        raise _UsageError(f"{self.prog}: error: {message} (see {self.prog} --help)")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``impactmaps`` command."""
    from . import __version__
    from .maps.lookup import SHIPPED_MAPS
    from .targets.options import STRUCTURE_KINDS

    parser = _Parser(prog="impactmaps", description=__doc__.splitlines()[0])
    parser.add_argument("--version", action="version", version=f"impactmaps {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    def add(name, help_text, handler):
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--json", action="store_true", help="print one JSON object")
        p.set_defaults(handler=handler)
        return p

    p = add("chart", "the normalised max-force chart (Figure 2), its data and lookup table", _cmd_chart)
    p.add_argument("--out", default="impactmaps-output", help="output directory (default ./impactmaps-output)")
    p.add_argument("--zeta-range", nargs=2, type=float, default=(0.005, 100.0), metavar=("A", "B"))
    p.add_argument("--zeta-count", type=int, default=60, help="log-spaced ζ values (≥ 2, default 60)")
    p.add_argument("--lambdas", nargs="+", type=float, default=None, help="λ values (default 0.05 … 20, 8 values)")
    p.add_argument("--workers", type=int, default=None, help="worker processes (default: all cores)")
    p.add_argument("--overwrite", action="store_true", help="replace an fmax_map.nc made with another grid")
    p.add_argument("--quiet", action="store_true", help="no progress bar")

    p = add("point", "simulate one (ζ, λ) point on a beam or plate", _cmd_point)
    _point_arguments(p)
    p.add_argument("--plot", default=None, metavar="FILE", help="write the normalised histories to an image file")

    p = add("asymptote", "closed-form asymptote: infinite beam, infinite plate or quasi-static", _cmd_asymptote)
    p.add_argument("which", choices=("infinite-beam", "infinite-plate", "quasi-static"))
    p.add_argument("--zeta", type=float, help="loss factor ζ (infinite-beam, infinite-plate)")
    p.add_argument("--lambda", dest="lambda_", type=float, help="relative stiffness λ (quasi-static)")

    p = add("classify", "regime of an impact at (ζ, λ)", _cmd_classify)
    p.add_argument("--zeta", type=float, required=True)
    p.add_argument("--lambda", dest="lambda_", type=float, required=True)
    p.add_argument("--structure", choices=STRUCTURE_KINDS, required=True)
    p.add_argument("--tolerance", type=float, default=0.1,
                   help="relative distance to an asymptote that counts as on it, in (0, 1] (default 0.1)")
    p.add_argument("--from-map", action="store_true", help="interpolate the shipped map instead of simulating")
    _point_arguments(p, with_target=False)

    p = add("lookup", "F̄max and regime from the shipped maps (no simulation)", _cmd_lookup)
    p.add_argument("--structure", choices=STRUCTURE_KINDS, required=True)
    p.add_argument("--theory", choices=sorted({t for _, t in SHIPPED_MAPS}), required=True)
    p.add_argument("--zeta", type=float)
    p.add_argument("--lambda", dest="lambda_", type=float)
    p.add_argument("--case", type=Path, help="a physical case file: gives the peak force in newtons too")

    p = add("sweep", "run a sweep described by a TOML file (resumable)", _cmd_sweep)
    p.add_argument("config", type=Path)
    p.add_argument("--workers", type=int, default=None, help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="run on a Dask cluster, e.g. tcp://host:8786 (needs the dask extra)")
    p.add_argument("--overwrite", action="store_true", help="replace a sweep.nc made by another configuration")
    p.add_argument("--quiet", action="store_true")

    for name, text, handler in (
            ("simulate", "simulate a physical case file (TOML) with the modal solver", _cmd_simulate),
            ("fd", "simulate a beam case file with the finite-difference elastic-plastic solver", _cmd_fd)):
        p = add(name, text, handler)
        p.add_argument("case", type=Path)
        p.add_argument("--out", default="impactmaps-output",
                       help="directory for history.csv, history.png, summary.json (default ./impactmaps-output)")

    p = add("halfspace", "sphere on a half-space with any contact law", _cmd_halfspace)
    p.add_argument("--law", required=True, help="a contact law (impactmaps laws lists them)")
    p.add_argument("--radius", type=float, required=True, help="sphere radius [m]")
    p.add_argument("--velocity", type=float, required=True, help="impact velocity [m/s]")
    p.add_argument("--mass", type=float, default=None, help="impactor mass [kg] (default: the solid sphere's)")
    p.add_argument("--material", default=None, help="impactor catalogue material (impactmaps materials)")
    p.add_argument("--target-material", default=None, help="target catalogue material")
    p.add_argument("--youngs-modulus", type=float, default=None, help="E [Pa] of the body without a --…material")
    p.add_argument("--poisson-ratio", type=float, default=None, help="ν of the body without a --…material")
    p.add_argument("--density", type=float, default=None, help="ρ [kg/m³] of the body without a --…material")
    p.add_argument("--yield-strength", type=float, default=None, help="yield strength [Pa] (plastic laws)")

    p = add("restitution", "coefficient of restitution e(β) of the Yigit–Christoforou law", _cmd_restitution)
    p.add_argument("--beta", type=float, required=True, help=f"impact number β in (0, {MAX_RESTITUTION_BETA:g}]")

    add("materials", "the material catalogue with its values (SI) and sources", _cmd_materials)
    add("laws", "the registered contact laws with their options and sources", _cmd_laws)
    return parser


def _point_arguments(p, with_target=True):
    if with_target:
        p.add_argument("--target", required=True, help="beam-ss, beam-cc, beam-cs, beam-cf, beam-ff, plate-ss, …")
        p.add_argument("--theory", default=None, help="euler|rayleigh|timoshenko or kirchhoff|mindlin")
        p.add_argument("--zeta", type=float, required=True)
        p.add_argument("--lambda", dest="lambda_", type=float, required=True)
    p.add_argument("--aspect", type=float, default=None, help="plate aspect ratio b/a (default 1)")
    p.add_argument("--slenderness", type=float, default=None, help="span/thickness (default 20)")
    p.add_argument("--position", type=float, default=None, help="impact point x0/L (or x0/a) (default 0.5)")
    p.add_argument("--position-y", type=float, default=None, help="impact point y0/b, plates (default 0.5)")
    p.add_argument("--cutoff-ratio", type=float, default=None, help="mode cut-off / contact frequency (default 40)")
    p.add_argument("--time-step-ratio", type=float, default=None,
                   help="upper bound of ω Δt (default: the solver's, ModalSettings)")
    p.add_argument("--no-check", action="store_true", help="skip the convergence re-run")


def _error_text(error: BaseException) -> str:
    if isinstance(error, MemoryError):
        return "out of memory: the run needs more memory than this machine has (reduce its size or duration)"
    if isinstance(error, OSError) and error.strerror:
        where = f": {error.filename}" if error.filename else ""
        return f"{error.strerror}{where}"
    return str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__


def _interrupted(error: BaseException) -> bool:
    """True if a KeyboardInterrupt is among the causes of ``error``."""
    seen = set()
    while error is not None and id(error) not in seen:
        if isinstance(error, KeyboardInterrupt):
            return True
        seen.add(id(error))
        error = error.__cause__ or error.__context__
    return False


def main(argv=None) -> int:
    """Entry point of the ``impactmaps`` command; returns the exit status.

    0 on success, 2 on bad input (one line on stderr; with ``--json`` also
    ``{"error": …}`` on stdout), 130 when interrupted (Ctrl-C).
    """
    from .maps.store import SweepInterrupted

    argv = sys.argv[1:] if argv is None else [str(a) for a in argv]
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
    except _UsageError as error:
        if "--json" in argv:
            print(dumps({"error": str(error)}))
        print(error, file=sys.stderr)
        return 2
    caught = []
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            values = args.handler(args)
    except SweepInterrupted as stop:
        print(f"impactmaps {args.command}: interrupted: {stop.saved} of {stop.total} points saved; "
              "run the same command to resume", file=sys.stderr)
        return 130
    except KeyboardInterrupt:
        print(f"impactmaps {args.command}: interrupted", file=sys.stderr)
        return 130
    except SystemError as error:  # Ctrl-C while compiled (numba) code returns reaches Python as this
        if not _interrupted(error):
            raise
        print(f"impactmaps {args.command}: interrupted", file=sys.stderr)
        return 130
    except (ValueError, OSError, MemoryError) as error:
        if args.json:
            print(dumps({"error": _error_text(error)}))
        print(f"impactmaps {args.command}: error: {_error_text(error)}", file=sys.stderr)
        return 2
    finally:
        seen = set()
        for warning in caught:
            text = str(warning.message)
            if text not in seen:
                seen.add(text)
                print(f"warning: {text}", file=sys.stderr)
    _emit(values, args.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
