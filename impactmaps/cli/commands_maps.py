"""Subcommands on the normalised (ζ, λ) maps: chart, sweep, point, classify, lookup, asymptote.

Each ``cmd_*`` takes the parsed arguments and returns the dict that ``main`` prints.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

from ..maps.family.map_family import MapFamily
from ..maps.compute.workers import MAX_WORKERS
from ._common import (announce_wide_band, case_model_warnings, check, check_shape_options, out_dir, plot_file,
                      refuse, save_figure, target_kind_and_supports, text_file)

__all__ = ["cmd_chart", "cmd_sweep", "cmd_point", "cmd_classify", "cmd_lookup", "cmd_asymptote",
           "SCHEDULER_TIMEOUT_S"]

#: Seconds to wait for a Dask scheduler (``sweep --scheduler``).
SCHEDULER_TIMEOUT_S = 5.0
#: Largest loss factor ζ the normalised commands accept: beyond it the infinite-structure
#: peak is below 1e-4 of the half-space's (F̄max ≈ 0.37 ζ^(-2/3) on the beam, 0.5/ζ on the
#: plate) and the beam's closed form loses its root (it fails near ζ = 1e250); the map
#: families' ζ range ends there too (:attr:`MapFamily.axis_ranges`).
ZETA_MAX = MapFamily.axis_ranges["zeta"][1]
#: Range of ζ (up to :data:`ZETA_MAX`) and λ a simulated point accepts (``point``, ``classify``):
#: the map families' (:attr:`MapFamily.axis_ranges`, where the reason is).
SIMULATED_RANGE = MapFamily.axis_ranges["lambda_"]


def cmd_chart(args) -> dict:
    from ..plotting.chart import (DEFAULT_STRUCTURE_LAMBDAS, DEFAULT_STRUCTURE_ZETA_COUNT, DEFAULT_ZETA_COUNT,
                                  chart_structures, check_chart_grid, make_chart)
    from ..maps.family.builtin_families import PLASTIC_LAWS, family_layout
    from ..maps.files.store_lock import store_lock
    from .chart_structure import STRUCTURE_OPTIONS, chart_structure

    if args.law in PLASTIC_LAWS:
        refuse(args, {"--case": "case", "--target": "target", **STRUCTURE_OPTIONS},
               "with an elastic-plastic --law (its chart is drawn from the shipped maps of the simply supported "
               "structures)")
        return _plastic_chart(args)
    refuse(args, {"--betas": "betas"}, f"with --law {args.law} (β is a number of the elastic-plastic laws "
           f"{', '.join(PLASTIC_LAWS)})")
    structure = chart_structure(args)  # None: the shipped chart
    structures = chart_structures(structure)
    zeta_count = args.zeta_count if args.zeta_count is not None else \
        (DEFAULT_ZETA_COUNT if structure is None else DEFAULT_STRUCTURE_ZETA_COUNT)
    lambdas = args.lambdas if args.lambdas is not None or structure is None else list(DEFAULT_STRUCTURE_LAMBDAS)
    family = family_layout(args.law)
    if lambdas is not None and family.chart_lambda_min > 0.0:
        for value in lambdas:
            check("--lambdas", value, family.chart_lambda_min, what=f"each {family.labels['lambda_name']}",
                  low_inclusive=True)
    check("--zeta-range", args.zeta_range[1], high=family.chart_zeta_max,
          what=f"the largest {family.labels['zeta_name']}", high_inclusive=True)
    check("--workers", args.workers, 1, MAX_WORKERS, "the number of worker processes",
          low_inclusive=True, high_inclusive=True)
    check_chart_grid(args.zeta_range, zeta_count, lambdas, args.law, len(structures))
    out = out_dir("--out", args.out)
    with store_lock(out / "fmax_map.nc", "--out"):
        paths = make_chart(out_dir=out, zeta_range=tuple(args.zeta_range), zeta_count=zeta_count,
                           lambdas=lambdas, structures=structures, progress=not args.quiet,
                           max_workers=args.workers, overwrite=args.overwrite, law=args.law)
    values = {key: str(value) for key, value in paths.items()}
    if structure is not None:
        values |= {"structures": [s.name for s in structures], "structure": structure.name,
                   "reference": structures[0].name}
    return values


def _plastic_chart(args) -> dict:
    """``chart --law yc|stronge``: F̄max, restitution, absorbed energy vs ζ at a few β for one λ,
    drawn from the shipped elastic-plastic maps (``--lambdas``: one λ; ``--betas``: the β)."""
    from ..plotting.chart import DEFAULT_PLASTIC_BETAS, DEFAULT_PLASTIC_LAMBDA, make_plastic_chart

    refuse(args, {"--workers": "workers", "--overwrite": "overwrite"},
           "with an elastic-plastic --law (the chart is drawn from the shipped maps, nothing is swept)")
    lambdas = args.lambdas or [DEFAULT_PLASTIC_LAMBDA]
    if len(lambdas) != 1:
        raise ValueError(f"--lambdas = {' '.join(f'{v:g}' for v in lambdas)} is invalid with --law {args.law}: "
                         "give one λ (the curves are β at one λ)")
    betas = getattr(args, "betas", None) or DEFAULT_PLASTIC_BETAS
    paths = make_plastic_chart(out_dir("--out", args.out), law=args.law, lambda_=lambdas[0], betas=betas)
    return {key: str(value) for key, value in paths.items()}


def cmd_sweep(args) -> dict:
    from ..maps.compute.config import load_sweep_config
    from ..maps.files.store_lock import store_lock

    check("--workers", args.workers, 1, MAX_WORKERS, "the number of worker processes",
          low_inclusive=True, high_inclusive=True)
    if args.scheduler is not None:
        refuse(args, {"--workers": "workers"}, "with --scheduler (the cluster has its own workers)")
    config = load_sweep_config(text_file("sweep file", args.config))  # parsed and checked before anything is written
    if config.output.exists() and not config.output.is_dir():
        raise ValueError(f"{args.config}: output = {str(config.output)!r} is a file, not a directory")
    output = out_dir(f"{args.config}: output", config.output)
    with store_lock(output / "sweep.nc", f"{args.config}: output"):
        return _run_sweep(args, replace(config, output=output))


def _run_sweep(args, config) -> dict:
    from ..maps.compute.config import run_sweep_config

    if args.scheduler is None:
        paths = run_sweep_config(config, progress=not args.quiet, overwrite=args.overwrite,
                                 max_workers=args.workers)
        return {key: str(value) for key, value in paths.items()}
    try:
        from dask.distributed import Client
    except ImportError:
        raise ValueError("--scheduler needs dask.distributed: pip install 'impactmaps[dask]'") from None
    try:
        client = Client(args.scheduler, timeout=SCHEDULER_TIMEOUT_S)
    except (OSError, TimeoutError) as error:
        raise ValueError(f"--scheduler = {args.scheduler!r} cannot be reached: {error}") from None
    with client:
        paths = run_sweep_config(config, progress=not args.quiet, overwrite=args.overwrite,
                                 executor=client.get_executor())
    return {key: str(value) for key, value in paths.items()} | {"scheduler": args.scheduler}



def _point_defaults(args) -> None:
    """Check the point options as typed, then fill in their defaults."""
    check("--zeta", args.zeta, SIMULATED_RANGE[0], ZETA_MAX, "the loss factor ζ", low_inclusive=True,
          high_inclusive=True)
    check("--lambda", args.lambda_, *SIMULATED_RANGE, "the relative stiffness λ", low_inclusive=True,
          high_inclusive=True)
    check_shape_options(args)
    check("--cutoff-ratio", args.cutoff_ratio, what="the mode cut-off / contact frequency")
    check("--time-step-ratio", args.time_step_ratio, what="the bound of ω Δt")
    for name, default in (("aspect", 1.0), ("slenderness", 20.0), ("position", 0.5), ("position_y", 0.5),
                          ("cutoff_ratio", 40.0)):
        if getattr(args, name) is None:
            setattr(args, name, default)


def _structure_from_args(args):
    from ..maps.family.structures import MapStructure
    from ..targets.options import default_theory

    kind, supports = target_kind_and_supports(args, args.target)
    _point_defaults(args)
    theory = args.theory or default_theory(kind)
    fractions = (args.position,) if kind == "beam" else (args.position, args.position_y)
    try:
        structure = MapStructure(kind=kind, theory=theory, supports=supports, aspect_ratio=args.aspect,
                                 slenderness=args.slenderness, impact_fraction=fractions)
        structure.build()
    except ValueError as error:
        raise ValueError(f"--target {args.target} --theory {theory}: {error}") from None
    return structure


def _settings_from_args(args):
    from ..solvers.modal_settings import ModalSettings

    options = {} if args.time_step_ratio is None else {"time_step_ratio": args.time_step_ratio}
    return ModalSettings(cutoff_ratio=args.cutoff_ratio, check_convergence=not getattr(args, "no_check", False),
                         **options)


def _simulate_point(structure, target, args, settings, record: bool):
    """The impact realising (--zeta, --lambda) on ``target``; a point no method answers
    within the mode cap is refused naming the options."""
    from ..solvers.modal import simulate_normalised
    from ..solvers.mode_budget import ModeBudgetError

    try:
        return simulate_normalised(target, args.zeta, args.lambda_, settings=settings, record=record)
    except ModeBudgetError as error:
        raise ValueError(
            f"--zeta = {args.zeta:g} with --lambda = {args.lambda_:g} is invalid on {structure.name}: "
            f"{error.reason}; valid range: a contact frequency ≤ {error.highest_frequency:.4g} rad/s "
            "(a larger --zeta or --lambda), or an impact --position farther from the boundary") from None


def _map_point(structure, args, settings) -> dict:
    """The (--zeta, --lambda) point as a sweep stores it (value, status: the same bits), its
    error stated with its floor (:func:`~impactmaps.maps.family.accuracy.stated_row`)."""
    from ..maps.family.accuracy import STATUSES, AccuracyControl, stated_row
    from ..maps.compute.points import METHODS
    from ..maps.family.map_family import RESULT_VARIABLES
    from ..maps.compute.linear_points import solve_points
    from ..solvers.modal_settings import ConvergenceWarning

    control = AccuracyControl(tolerance=settings.tolerance)
    with warnings.catch_warnings():  # the status says what the refinement found
        warnings.simplefilter("ignore", ConvergenceWarning)
        row = stated_row(solve_points(structure, [(args.zeta, args.lambda_)],
                                      replace(settings, check_convergence=False), control=control)[0])
    values = {name: (int(row[name]) if dtype.startswith("i") else float(row[name]))
              for name, (dtype, *_rest) in RESULT_VARIABLES.items() if name in row}
    values["status"] = STATUSES[values["status"]]
    values["method"] = METHODS[values["method"]] if values["method"] >= 0 else "none"
    return values


def cmd_point(args) -> dict:
    from ..maps.family.regimes import classify, infinite_structure_peak, quasi_static_peak

    structure = _structure_from_args(args)
    target = structure.build()
    settings = _settings_from_args(args)
    plot = getattr(args, "plot", None)
    plot = None if plot is None else plot_file("--plot", plot)
    checked = settings.check_convergence
    with warnings.catch_warnings():
        if checked and target.point_load_diverges:  # the map point's own warning below says it
            from .._checks import ModelValidityWarning

            warnings.filterwarnings("ignore", message="point load", category=ModelValidityWarning)
        result = _simulate_point(structure, target, args, replace(settings, check_convergence=False),
                                 record=plot is not None)
    reflection = float(target.reflection_time(result.contact_frequency))
    values = {
        "structure": structure.name,
        "zeta": args.zeta,
        "lambda": args.lambda_,
        **result.normalised_summary(),
        "method": result.method,
    }
    if checked:
        # the value a sweep stores for this point, with its error and status (the same bits)
        if target.point_load_diverges:
            from ..maps.family.structures import warn_point_loaded_mindlin

            warn_point_loaded_mindlin("this Mindlin point strikes", stacklevel=1)
        mapped = _map_point(structure, args, settings)
        if mapped["status"] == "unresolved":  # no map value: keep this run's, say why it is not vouched for
            values.update(status="unresolved", status_note=(
                "the toolkit does not vouch for this value: the contact frequency lies beyond the range of the "
                f"{structure.theory} theory (or the point needs more modes than the cap); see "
                "impactmaps.targets.shear_range"))
        else:
            values.update(mapped)
        values["converged"] = values["status"] not in ("sensitive", "unresolved")
    else:
        values["converged"] = None
        values["status"] = "unchecked"
        values["converged_note"] = "not checked (--no-check)"
    values["regime"] = str(classify(values["fmax_normalised"], args.zeta, args.lambda_, structure.kind,
                                    peak_time=values["peak_time_normalised"], reflection_time=reflection,
                                    tolerance=getattr(args, "tolerance", 0.1)))
    values.update({
        "halfspace_fmax": 1.0,
        "quasi_static_fmax": float(quasi_static_peak(args.lambda_)),
        "infinite_structure_fmax": float(infinite_structure_peak(args.zeta, structure.kind)),
        "reflection_time_normalised": reflection,
    })
    if not math.isfinite(reflection):
        values["reflection_time_note"] = "no support or edge reflects waves back to the impact point"
    if result.method == "infinite-structure-asymptote":
        values["asymptote"] = result.details.asymptote
    if plot is not None:
        values["plot"] = save_figure(result, plot, normalised=True)
        values["plot_note"] = "the history of the run at the given settings (the value above is the refined one)"
    return values


def cmd_asymptote(args) -> dict:
    from ..closed_forms import asymptotes, infinite_beam

    if getattr(args, "case", None) is not None:
        return _case_asymptote(args)
    if args.which == "half-space":
        raise ValueError("the half-space asymptote needs a physical case: give --case CASE.toml "
                         "(in normalised form it is F̄max = 1, contact time π)")
    if args.which == "quasi-static":
        refuse(args, {"--zeta": "zeta"}, "with the quasi-static asymptote (it depends on λ only)")
        if args.lambda_ is None:
            raise ValueError("--lambda is required for the quasi-static asymptote (valid range (0, inf))")
        check("--lambda", args.lambda_, what="the relative stiffness λ")
        return {
            "asymptote": args.which,
            "lambda": args.lambda_,
            "fmax_normalised": float(asymptotes.quasi_static_peak(args.lambda_)),
            "contact_time_normalised": float(asymptotes.quasi_static_contact_time(args.lambda_)),
            "impacts": 1,
        }
    refuse(args, {"--lambda": "lambda_"}, f"with the {args.which} asymptote (it depends on ζ only)")
    if args.zeta is None:
        raise ValueError(f"--zeta is required for the {args.which} asymptote (valid range (0, inf))")
    check("--zeta", args.zeta, high=ZETA_MAX, what="the loss factor ζ", high_inclusive=True)
    if args.which == "infinite-plate":
        peak, contact = asymptotes.infinite_plate_peak(args.zeta), asymptotes.infinite_plate_contact_time(args.zeta)
    else:
        peak, contact = infinite_beam.infinite_beam_peak(args.zeta), infinite_beam.infinite_beam_contact_time(args.zeta)
    values = {"asymptote": args.which, "zeta": args.zeta, "fmax_normalised": float(peak),
              "contact_time_normalised": float(contact), "impacts": 1}
    if not math.isfinite(float(contact)):
        values["contact_time_note"] = "the sphere never separates from the infinite structure at this ζ"
    if args.which == "infinite-beam":
        values.update(_beam_impacts(args.zeta))
    return values


def _case_asymptote(args) -> dict:
    """The asymptote of a physical case, for its own contact law (``--case``)."""
    from ..cases import load_case
    from ..closed_forms.law_asymptotes import asymptote
    from ..validity import warn_if_invalid

    refuse(args, {"--zeta": "zeta", "--lambda": "lambda_"}, "with --case (the case gives them)")
    case = load_case(args.case)
    target = None if args.which == "half-space" else case.target
    result = asymptote(args.which, target, case.law, case.impactor_mass, case.velocity)
    values = {"asymptote": args.which, "case": case.name, "law": case.law_name, **result.summary()}
    if not math.isfinite(result.contact_time):
        values["contact_time_note"] = "the sphere does not separate within the run"
    values["model_warnings"] = warn_if_invalid(case.sphere, case.target_material, case.law, case.target, result)
    return values


def _beam_impacts(zeta: float) -> dict:
    """How often the infinite beam is struck: once, or again after the first separation."""
    from ..closed_forms.infinite_beam import (
        critical_beam_loss_factor,
        recontact_beam_loss_factor,
    )

    recontact, critical = recontact_beam_loss_factor(), critical_beam_loss_factor()
    if recontact < zeta < critical:
        return {"impacts": None, "repeated_impacts": True,
                "impacts_note": f"{recontact:.6g} < ζ < {critical:.6g}: the sphere still moves towards the beam "
                                "when it first separates and strikes again (at least 2 impacts; the later "
                                "ones: impactmaps.closed_forms.infinite_beam.infinite_beam_force); "
                                "contact_time_normalised is the first contact's"}
    return {"impacts": 1, "repeated_impacts": False}


def cmd_classify(args) -> dict:
    check("--tolerance", args.tolerance, 0.0, 1.0, "the relative distance to an asymptote",
           high_inclusive=True)
    if args.from_map:
        from ..cases.case_lookup import lookup
        from ..targets.options import default_theory

        refuse(args, {"--aspect": "aspect", "--slenderness": "slenderness", "--position": "position",
                       "--position-y": "position_y", "--cutoff-ratio": "cutoff_ratio",
                       "--time-step-ratio": "time_step_ratio", "--no-check": "no_check"},
                "with --from-map (the shipped maps are for centre impacts on SS beams and square plates)")
        check("--zeta", args.zeta, what="the loss factor ζ")
        check("--lambda", args.lambda_, what="the relative stiffness λ")
        theory = default_theory(args.kind)
        found = lookup(args.zeta, args.lambda_, kind=args.kind, theory=theory,
                       tolerance=args.tolerance)
        return {"regime": found.regime, "fmax_normalised": found.fmax_normalised, "source": f"map {found.map_name}"}
    args.target = "beam-ss" if args.kind == "beam" else "plate-ss"
    args.theory = None
    point = cmd_point(args)
    return {"regime": point["regime"], "fmax_normalised": point["fmax_normalised"],
            "source": f"simulation {point['structure']}", "converged": point["converged"]}


def cmd_lookup(args) -> dict:
    """``impactmaps lookup``: a point of a shipped map (:func:`~impactmaps.maps.read.lookup.point_answer`,
    straight to the reader), or a case (:func:`_lookup_case`)."""
    from ..maps.family.accuracy import status_notes
    from ..maps.read.lookup import point_answer

    if args.case is not None:
        return _lookup_case(args)
    refuse(args, {"--no-build": "no_build", "--quiet": "quiet"}, "without --case (only the lookup of a case builds map tiles)")
    if args.zeta is None or args.lambda_ is None or args.kind is None:
        raise ValueError("give --kind, --zeta and --lambda (and --theory: default the classical one, euler or "
                         "kirchhoff), or --case CASE.toml")
    if args.theory is None:
        from ..targets.options import default_theory

        args.theory = default_theory(args.kind)
    from ..maps.family.builtin_families import PLASTIC_LAWS

    if args.law in PLASTIC_LAWS:
        refuse(args, {"--slenderness": "slenderness"}, "with an elastic-plastic law (its maps are at slenderness 20)")
        return _lookup_plastic_numbers(args, point_answer)
    refuse(args, {"--beta": "beta"}, f"with the {args.law or 'linear'} law (β is a number of the {', '.join(PLASTIC_LAWS)} maps)")
    check("--zeta", args.zeta, what="the loss factor ζ")
    check("--lambda", args.lambda_, what="the relative stiffness λ")
    law = args.law or "linear"
    slenderness = getattr(args, "slenderness", None)
    if slenderness is not None:
        check("--slenderness", slenderness, 10.0, what="span/thickness (the thickest slenderness member is 10)",
              low_inclusive=True)
    try:
        found = point_answer(args.zeta, args.lambda_, kind=args.kind, theory=args.theory, law=law,
                             slenderness=slenderness)
    except ValueError as error:  # name the options as the user typed them
        raise ValueError(str(error).replace("loss_factor", "--zeta").replace("relative_stiffness", "--lambda")) \
            from None
    values = {"fmax_normalised": found.fmax_normalised, "fmax_error": found.fmax_error, "status": found.status,
              **status_notes(found.status), "regime": found.regime, "map": found.map_name, "law": law}
    return announce_wide_band(values, "fmax_normalised", "fmax_error",
                              f"impactmaps point --zeta {args.zeta:g} --lambda {args.lambda_:g} --target {args.kind}-… "
                              f"--theory {args.theory}, or impactmaps simulate on a case file")


def _lookup_case(args) -> dict:
    """``lookup --case CASE.toml``: the case built from its file, then answered by
    :func:`impactmaps.lookup` (its shipped map or an on-demand tile), with its model warnings."""
    import sys
    import time

    from ..cases.case import load_case
    from ..cases.case_answer import case_map_law
    from ..cases.case_lookup import lookup

    refuse(args, {"--zeta": "zeta", "--lambda": "lambda_", "--beta": "beta", "--slenderness": "slenderness"},
           "with --case (the case gives its numbers)")
    case = load_case(args.case)
    for option, given, wanted in (("--kind", args.kind, lambda: case.target_type),
                                  ("--theory", args.theory, lambda: getattr(case.target, "theory", None)),
                                  ("--law", args.law, lambda: case_map_law(case))):
        if given is not None and given != wanted():
            raise ValueError(f"{option} = {given} contradicts the case ({wanted()}); leave it out: "
                             "the case says which map describes it")
    notify = None if args.quiet else (lambda line: print(line, file=sys.stderr))
    start = time.perf_counter()
    progress = None if args.quiet else (lambda done, total: print(
        f"  {done}/{total} points ({time.perf_counter() - start:.0f} s)", file=sys.stderr))
    found = lookup(case=case, build=not args.no_build, notify=notify, progress=progress)
    found = announce_wide_band(found, "peak_force_N", "peak_force_error_N", f"impactmaps simulate {args.case}")
    return found | case_model_warnings(case, found.get("peak_force_N"))


def _lookup_plastic_numbers(args, lookup) -> dict:
    """``lookup --law yc|stronge|epp --beta B --zeta Z --lambda L``: the plastic map at (β, ζ, λ)."""
    from ..maps.family.accuracy import status_notes

    beta = getattr(args, "beta", None)
    if beta is None:
        raise ValueError(f"--beta is required with --law {args.law} (the impact number; valid range (0, inf))")
    check("--beta", beta, what="the impact number β")
    check("--zeta", args.zeta, what="the loss factor ζ(m, K_y)")
    check("--lambda", args.lambda_, what="the relative stiffness K_st/K_y")
    found = lookup(beta, args.zeta, args.lambda_, kind=args.kind, theory=args.theory, law=args.law)
    return announce_wide_band({"fmax_normalised": found.fmax_normalised, "fmax_error": found.fmax_error,
            "restitution": found.restitution, "restitution_error": found.restitution_error,
            "absorbed_energy_fraction": found.absorbed_energy_fraction,
            "absorbed_energy_error": found.absorbed_energy_error, "status": found.status,
            **status_notes(found.status), "map": found.map_name, "law": args.law},
        "fmax_normalised", "fmax_error", "simulate a case file with this law")
