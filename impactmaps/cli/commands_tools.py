"""Subcommands that help write and check a case file (init, check) and prepare the
installation (warm-up).

``init`` writes a commented case file to start from; ``check`` validates one without
running it and prints what the run would be: the numbers of its law (the vocabulary of
``docs/output_keys.rst``), the map that describes it and the regime it reads there, and
the scales of the run.
"""

from __future__ import annotations

import math
from pathlib import Path

__all__ = ["CASE_TEMPLATES", "cmd_init", "cmd_check", "cmd_warm_up"]

_HEADER = """# {title}
#
# Written by `impactmaps init {template}`. Check it with `impactmaps check {file}` (validates and
# prints the derived numbers without running), run it with `impactmaps {run} {file}`.
# All quantities in SI units; materials from the catalogue (`impactmaps materials`).
# Every key is documented in the user guide (docs/cases.rst); an unknown key is an error.
"""

_IMPACTOR = """
[impactor]
radius = 0.00635                # sphere radius R [m] (12.7 mm diameter)
material = "bearing-steel-52100"   # a hardened steel ball; catalogue name, or an inline table {{youngs_modulus, poisson_ratio, density, yield_strength}}
# mass = 0.0084                 # [kg]; default: the solid sphere's, density x (4/3) pi R^3
velocity = {velocity}                  # approach velocity V0 [m/s]
"""

#: The tail of the plate templates: Hertz contact and the run's time limit.
_HERTZ_RUN = """
[contact]
law = "hertz"

[solver]
duration = {duration}                # time limit [s]
"""

CASE_TEMPLATES = {
    "beam": ("a steel ball on a simply supported aluminium beam (Hertz contact)", "simulate", _IMPACTOR.format(
        velocity="1.0") + """
[target]
type = "beam"
length = 0.5                    # span L [m]
width = 0.02                    # [m]
height = 0.02                   # [m], in the impact direction
material = "aluminium-6061-t6"
supports = "ss"                 # "ss", "cc", "cs", "cf", "ff" (left end, right end)
theory = "euler"                # "euler", "rayleigh", "timoshenko"
impact_position = 0.25          # x0 [m] from the left end (here mid-span)

[contact]
law = "hertz"                   # "hertz", "linear", "yigit-christoforou", "stronge" (impactmaps laws)

[solver]
duration = 0.005                # time limit [s]; the run stops earlier once re-impact is impossible
# check_convergence = true      # re-run with a doubled mode cut-off and report converged: true/false
"""),
    "plate": ("a steel ball on a simply supported steel plate (Hertz contact)", "simulate", _IMPACTOR.format(
        velocity="2.0") + """
[target]
type = "plate"
length_x = 0.25                 # [m]
length_y = 0.25                 # [m]
thickness = 0.004               # [m]
material = "structural-steel"
edges = "SSSS"                  # one letter per edge: S (simply supported), C (clamped), F (free)
# edges = "CCCC"                # a clamped plate: any edges with either theory
theory = "kirchhoff"            # "kirchhoff" or "mindlin"
impact_point = [0.125, 0.125]   # [x0, y0] [m] (here the centre)
""" + _HERTZ_RUN.format(duration="0.005")),
    "laminate": ("a steel ball on a simply supported cross-ply graphite/epoxy plate (Hertz contact)", "simulate",
                 _IMPACTOR.format(velocity="3.0") + """
[target]
type = "plate"
length_x = 0.2                  # [m]
length_y = 0.2                  # [m]
theory = "mindlin"              # laminates: first-order shear deformation
edges = "SSSS"
# edges = "CCCC"                # a clamped window (the drop-weight test: examples/drop_weight_quasi_isotropic.toml)
impact_point = [0.1, 0.1]       # [m]
# the stacking sequence (D16, D26 kept; an unsymmetric layup, B ≠ 0, is refused): a catalogue ply, its angles [deg], mirrored when symmetric
layup = { ply = "t300-934", angles_deg = [0, 90, 0, 90, 0], symmetric = true, ply_thickness = 0.000269 }
# yield_strength = 3.0e8        # the laminate's contact strength [Pa], for the plastic laws
""" + _HERTZ_RUN.format(duration="0.002")),
    "fd": ("a steel ball on a simply supported steel beam, finite-difference elastic-plastic beam", "fd",
           _IMPACTOR.format(velocity="0.5") + """
[target]
type = "beam"                   # the finite-difference solver takes isotropic beams only
length = 0.78                   # span [m]
width = 0.06                    # [m]
height = 0.0278                 # [m], in the impact direction
material = "structural-steel"   # needs a yield strength (the beam yields)
supports = "ss"
impact_position = 0.39          # [m], mid-span

[contact]
law = "stronge"                 # the refined Stronge law (the default of the fd solver)

[solver]
kind = "fd"                     # the finite-difference Rayleigh beam
duration = 0.005                # simulated time [s] (required: the run always covers it)

[fd]
n_elements = 200                # beam elements along the span
n_half_layers = 10              # layers through half the height (plastic zones)
plastic = true
"""),
}


def cmd_init(args) -> dict:
    template = CASE_TEMPLATES[args.template]
    path = Path(args.file if args.file is not None else f"{args.template}.toml")
    if path.is_dir():
        raise ValueError(f"FILE = {str(path)!r} is a directory: give a file name (e.g. {args.template}.toml)")
    if path.exists() and not args.overwrite:
        raise ValueError(f"FILE = {str(path)!r} exists: give another name, or --overwrite to replace it")
    title, run, body = template
    text = _HEADER.format(title=title, template=args.template, file=path.name, run=run) + \
        f'\nname = "{title}"\n' + body
    try:
        path.write_text(text, encoding="utf-8")
    except OSError as error:
        raise ValueError(f"FILE = {str(path)!r} cannot be written: {error.strerror or error}") from None
    return {"case": str(path), "kind": args.template, "next": f"impactmaps check {path}; impactmaps {run} {path}"}


def cmd_check(args) -> dict:
    """Validate a case file and report its derived numbers, without running it."""
    from ..cases import case_numbers, load_case
    from ..contact.contact_scale import reference_contact_stiffness
    from ._common import case_model_warnings

    case = load_case(args.case)
    numbers = case_numbers(case)
    mass, velocity = case.impactor_mass, case.velocity
    omega = math.sqrt(float(reference_contact_stiffness(case.law, mass, velocity)) / mass)
    values = {
        "case": case.name,
        "valid": True,
        "solver": case.solver_kind,
        "target_type": case.target_type,
        "law": case.law_name,
        "impactor_mass_kg": mass,
        "velocity_m_s": velocity,
        "impact_energy_J": 0.5 * mass * velocity**2,
        **{key: numbers.get(key) for key in ("vocabulary", "beta", "zeta", "lambda", "lambda_basis",
                                               "zeta_linearised", "lambda_linearised") if key in numbers},
        "force_scale_N": numbers["force_scale_N"],
        "static_stiffness_N_m": numbers["static_stiffness_N_m"],
        "contact_frequency_rad_s": omega,
        "halfspace_contact_time_s": math.pi / omega,
        "time_limit_s": case.duration,
    }
    if case.solver_kind == "modal" and case.fd_settings is not None:
        values["valid"] = False
        values["valid_note"] = ("the [fd] section is read by the finite-difference solver only: simulate refuses "
                                "this case (run impactmaps fd, or set [solver] kind = \"fd\")")
    values.update(_map_reading(case))
    values.update(_estimated_cost(case, values))
    values.update(case_model_warnings(case, values.get("map_peak_force_N")))
    notes = {"beta": f"the {case.law_name} law has no yield indentation: β is a number of the elastic-plastic laws",
             "time_limit_s": "no [solver] duration: the run stops once re-impact is impossible (or at "
                             "max_time_ratio contact times)"}
    halfspace = "a half-space has no structure stiffness (K_st is infinite)"
    out = {}
    for key, value in values.items():
        out[key] = value
        if value is None and f"{key}_note" not in values:
            out[f"{key}_note"] = notes.get(key, halfspace if case.target_type == "halfspace" else
                                           "does not exist for this case")
    return out


def _estimated_cost(case, values: dict) -> dict:
    """The modal run's estimate (:func:`impactmaps.solvers.modal.estimate_run`: modes, steps,
    history rows, memory, time), keys ``estimated_…``; a run the budget refuses makes the
    case invalid (``valid_note`` says why)."""
    from ..solvers.run_budget import LONG_RUN_SECONDS, MEMORY_LIMIT_BYTES

    if case.solver_kind != "modal":
        return _estimated_fd_cost(case, values)
    from ..solvers.modal import estimate_run

    import warnings

    try:
        with warnings.catch_warnings():  # an estimate only counts: its first guesses (the half-space contact
            warnings.simplefilter("ignore")  # radius) warn of what the run need not meet; model_warnings say it
            cost = estimate_run(case.target, case.law, case.impactor_mass, case.velocity, settings=case.settings,
                                record=True, time_step=case.time_step)
    except ValueError as error:  # the run would be refused before it starts
        values["valid"] = False
        values["valid_note"] = f"simulate refuses this case: {error}"
        return {}
    out = {f"estimated_{key}": value for key, value in cost.items()}
    out["estimated_memory_MiB"] = out.pop("estimated_memory_bytes") / 2**20
    if cost["memory_bytes"] > MEMORY_LIMIT_BYTES:
        values["valid"] = False
        values["valid_note"] = (f"simulate refuses this case: the run may take {cost['memory_bytes'] / 2**30:.3g} GiB "
                                f"(limit {MEMORY_LIMIT_BYTES / 2**30:g} GiB)")
    out["estimated_cost_note"] = (
        "before any run, from the mode budget and the run budget (impactmaps.solvers.run_budget): seconds on the "
        f"2-core reference machine (runs above {LONG_RUN_SECONDS:g} s are announced), runs = 2 with the convergence "
        "check's re-run at twice the cut-off; a first run on an empty numba cache also compiles the integrator "
        "(impactmaps warm-up does that once)")
    if cost["time_step_s"] is None:
        out["estimated_time_step_s_note"] = "the infinite-structure solution answers: nothing is integrated"
    return out


def _estimated_fd_cost(case, values: dict) -> dict:
    """The finite-difference run's estimate (:func:`impactmaps.fd.estimate_fd`, arithmetic only),
    keys ``estimated_…``; with ``[solver] check_convergence`` the re-run on twice the elements
    counted in; a run the budget refuses makes the case invalid."""
    from dataclasses import replace

    from ..fd import estimate_fd
    from ..solvers.run_budget import LONG_RUN_SECONDS

    settings = replace(case.fd_settings, duration=case.duration)
    cost = estimate_fd(case.target, case.law, case.impactor_mass, case.velocity, settings=settings,
                       material=case.target_material)
    runs, memory, seconds = 1, cost["memory_bytes"], cost["seconds"]
    if case.settings.check_convergence:
        fine = estimate_fd(case.target, case.law, case.impactor_mass, case.velocity, material=case.target_material,
                           settings=replace(settings, n_elements=2 * int(case.fd_beam.n_elements)))
        runs, memory, seconds = 2, max(memory, fine["memory_bytes"]), seconds + fine["seconds"]
    if cost["refused"] is not None:
        values["valid"] = False
        values["valid_note"] = f"fd refuses this case: {cost['refused']}"
    return {"estimated_method": "finite-difference", "estimated_time_step_s": cost["time_step_s"],
            "estimated_expected_steps": cost["steps"], "estimated_history_rows": cost["history_rows"],
            "estimated_memory_MiB": memory / 2**20, "estimated_seconds": seconds, "estimated_runs": runs,
            "estimated_cost_note": (
                "before any run, from the grid's stability limit and the run budget (impactmaps.solvers.run_budget): "
                f"seconds on the 2-core reference machine (runs above {LONG_RUN_SECONDS:g} s are announced), runs = 2 "
                "with the convergence check's re-run on twice the elements")}


def _map_reading(case) -> dict:
    """What a shipped map says of the case (no tile is built), or why none does."""
    if case.target_type == "halfspace":
        return {"regime": "half-space", "map": None, "map_note": "a half-space needs no map"}
    from ..cases.case_lookup import lookup

    try:
        found = lookup(case=case, build=False)
    except ValueError as error:
        text = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
        text = text.removeprefix("no shipped map covers this case: ")
        return {"regime": None, "regime_note": "no shipped map reads this case: " + text, "map": None,
                "map_note": "impactmaps lookup --case builds an on-demand map tile where one can describe it"}
    from ._common import announce_wide_band

    reading = {"regime": found.get("regime"), "map": found.get("map"),
               "map_peak_force_N": found.get("peak_force_N"), "map_peak_force_error_N": found.get("peak_force_error_N")}
    reading = announce_wide_band(reading, "map_peak_force_N", "map_peak_force_error_N",
                                 f"impactmaps simulate {case.source or 'CASE.toml'}")
    if reading["regime"] is None:
        reading["regime_note"] = "the elastic-plastic maps have no regime classification"
    return reading


def cmd_warm_up(args) -> dict:
    """Compile the modal solver's kernels into numba's cache (``impactmaps warm-up``)."""
    from ..maps.compute.workers import MAX_WORKERS
    from ._common import check
    from .._compile.background_warm_up import mark_warm
    from ..solvers.warm_up import warm_up

    workers = 2 if args.workers is None else args.workers
    check("--workers", workers, 1, MAX_WORKERS, "worker processes", low_inclusive=True, high_inclusive=True)
    done = warm_up(int(workers))
    mark_warm(done)
    return {**done, "note": "the first integrating command now loads the compiled kernels instead of compiling "
                            "them; run again after upgrading impactmaps or numba"}
