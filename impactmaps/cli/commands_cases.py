"""Subcommands on physical cases and the catalogues: simulate, fd, halfspace, restitution,
materials, laws.

Each ``cmd_*`` takes the parsed arguments and returns the dict that ``main`` prints.
"""

from __future__ import annotations

import math
import sys

from ._common import check, material_from_args, out_dir, plain_text, refuse, refuse_ignored_fd, save_figure

__all__ = ["cmd_simulate", "cmd_fd", "cmd_halfspace", "cmd_restitution", "cmd_materials", "cmd_laws"]

def _run_case_command(args, solver) -> dict:
    from ..cases import load_case, run_case, write_case_outputs

    out = out_dir("--out", args.out)
    if getattr(args, "vary", None) is not None:
        from .study import run_study

        return run_study(args.case, args.vary, out, solver=solver, progress=not args.quiet)
    case = load_case(args.case, solver=solver)
    refuse_ignored_fd(case, args.case)
    result, summary = run_case(case)
    paths = write_case_outputs(case, result, out)
    summary = dict(summary)
    if result.history is not None:
        paths["figure"] = out / "history.png"
        save_figure(result, paths["figure"], normalised=False)
    else:
        summary["history_note"] = f"no history: answered by the {result.details.asymptote} asymptote (scalars only)"
    summary["outputs"] = {key: str(value) for key, value in paths.items()}
    return summary


def cmd_simulate(args) -> dict:
    return _run_case_command(args, None)


def cmd_fd(args) -> dict:
    return _run_case_command(args, "fd")


def cmd_halfspace(args) -> dict:
    from ..contact import Sphere, law_for_sphere
    from ..closed_forms.halfspace import halfspace_impact
    from ..validity import warn_if_invalid

    if args.material is not None and args.target_material is not None:
        refuse(args, {"--youngs-modulus": "youngs_modulus", "--poisson-ratio": "poisson_ratio",
                       "--density": "density"},
                "with both --material and --target-material (explicit values stand for a body without a name)")
    from .._toml import UNIT_LIMITS
    from ..cases.case import IMPACTOR_RANGES

    for option, value, key, what in (("--radius", args.radius, "radius", "the sphere radius [m]"),
                                     ("--velocity", args.velocity, "velocity", "the impact velocity [m/s]"),
                                     ("--mass", args.mass, "mass", "the impactor mass [kg]")):
        low, high = IMPACTOR_RANGES[key]
        check(option, value, low, high, what, high_inclusive=True)
    for option, value, unit in (("--youngs-modulus", args.youngs_modulus, "Pa"), ("--density", args.density, "kg/m^3"),
                                ("--yield-strength", args.yield_strength, "Pa")):
        check(option, value, 0.0, UNIT_LIMITS[unit], f"the value [{unit}]", high_inclusive=True)
    impactor_material = material_from_args(args, "", "impactor")
    target_material = material_from_args(args, "target_", "target")
    sphere = Sphere(args.radius, impactor_material, args.mass)
    law = law_for_sphere(args.law, sphere, target_material, **_law_options(args.law_option))
    result = halfspace_impact(law, sphere.mass, args.velocity)
    summary = result.summary()
    return {
        "law": args.law,
        "impactor_mass_kg": float(sphere.mass),
        **{key: summary[key] for key in ("peak_force_N", "first_contact_duration_s", "max_indentation_m",
                                         "permanent_indentation_m", "restitution", "energy_loss_J")},
        "model_warnings": warn_if_invalid(sphere, target_material, law, None, result),
    }


def _law_options(texts) -> dict:
    """``{name: value}`` of the ``--law-option NAME=VALUE`` arguments (numbers)."""
    options = {}
    for text in texts or ():
        name, sep, value = str(text).partition("=")
        try:
            number = float(value)
        except ValueError:
            number = math.nan
        if not sep or not name.strip() or not math.isfinite(number):
            raise ValueError(f"--law-option = {text!r} is invalid: give NAME=VALUE with a finite number "
                             "(e.g. sphere_compliance=0.5; impactmaps laws lists each law's options)")
        options[name.strip()] = number
    return options



#: Largest impact number ``restitution`` takes (the documented range; the closed form holds for
#: any finite β, but β = 10⁸ is already an impact 10⁸ times the yield velocity).
MAX_RESTITUTION_BETA = 1e8


def cmd_restitution(args) -> dict:
    from ..closed_forms.halfspace import restitution

    check("--beta", args.beta, 0.0, MAX_RESTITUTION_BETA, "the impact number β", high_inclusive=True)
    return {"beta": args.beta, "restitution": float(restitution(args.beta))}


def cmd_materials(args) -> dict:
    from dataclasses import fields

    from ..materials import CATALOGUE, SOURCES

    out = {}
    for name, entry in sorted(CATALOGUE.items()):
        values = {"kind": type(entry).__name__}
        values |= {f.name: getattr(entry, f.name) for f in fields(entry) if f.init and not f.name.startswith("_")}
        source, verified, unverified = SOURCES[name]
        out[name] = values | {"source": source, "verified": list(verified), "unverified": dict(unverified)}
    return {"materials": out, "units": "SI: moduli and strengths [Pa], density [kg/m³], thickness [m]",
            "sources_note": "verified: the values read in the source; unverified: each other value with the reason "
                            "(full citations beside each entry of impactmaps.materials.CATALOGUE)"}


def cmd_laws(args) -> dict:
    import inspect

    from ..contact import available_contact_laws, contact_law_class
    from ..contact.plastic.fe_agreement import FE_AGREEMENT_RANGE, fe_agreement

    out = {}
    for name in available_contact_laws():
        cls = contact_law_class(name)
        module = sys.modules[cls.__module__]
        options = {p.name: (None if p.default is inspect.Parameter.empty else p.default)
                   for p in inspect.signature(cls).parameters.values()}
        out[name] = {"class": f"{cls.__module__}.{cls.__name__}",
                     "description": plain_text((module.__doc__ or cls.__doc__ or "").strip().splitlines()[0]),
                     "options": options}
        measured = fe_agreement(name)
        if measured is not None:
            out[name]["fe_agreement"] = {quantity: f"{low:+.1%} to {high:+.1%}" for quantity, (low, high) in
                                         measured.items()}
    return {"laws": out, "options_note": "null: required (SI units); case files build them from the materials",
            "fe_agreement_note": f"error against axisymmetric finite elements: {FE_AGREEMENT_RANGE}"}


