"""impactmaps — low-velocity impact of a sphere on beams and plates.

Force histories for physical cases, the dimensionless (β, λ, ζ) picture of
Christoforou & Yigit (1998), the normalised maximum-force maps, regimes and design
lookups, all verified against exact solutions.

The public API is re-exported here lazily (importing ``impactmaps`` stays cheap; each
name loads its module on first use)::

    import impactmaps
    impactmaps.restitution(10.0)                     # e(β), Yigit–Christoforou law
    impactmaps.lookup(1.198, 0.425, kind="plate", theory="kirchhoff")  # or lookup(case=load_case(...))
    impactmaps.simulate(target, law, mass, velocity)  # modal solver, any target
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_EXPORTS = {
    # solvers
    "simulate": "impactmaps.solvers.modal",
    "simulate_normalised": "impactmaps.solvers.modal",
    "simulate_batch": "impactmaps.solvers.modal",
    "ModalSettings": "impactmaps.solvers.modal",
    "ImpactResult": "impactmaps.result",
    "halfspace_impact": "impactmaps.closed_forms.halfspace",
    "restitution": "impactmaps.closed_forms.halfspace",
    "simulate_fd": "impactmaps.fd",
    "FDBeam": "impactmaps.fd",
    # targets, materials, contact
    "Beam": "impactmaps.targets.beams.beam",
    "Plate": "impactmaps.targets.plates.plate",
    "ModalBasis": "impactmaps.targets.base",
    "HalfSpace": "impactmaps.targets.halfspace",
    "IsotropicMaterial": "impactmaps.materials",
    "Ply": "impactmaps.materials",
    "Laminate": "impactmaps.materials",
    "material": "impactmaps.materials",
    "Sphere": "impactmaps.contact",
    "law_for_sphere": "impactmaps.contact",
    "contact_law": "impactmaps.contact",
    "available_contact_laws": "impactmaps.contact",
    "law_options": "impactmaps.contact",
    "ContactPair": "impactmaps.contact",
    # dimensionless framework
    "realise": "impactmaps.dimensionless",
    "loss_factor_plate": "impactmaps.dimensionless",
    "loss_factor_beam": "impactmaps.dimensionless",
    "relative_stiffness": "impactmaps.dimensionless",
    "impact_number": "impactmaps.dimensionless",
    # maps
    "sweep": "impactmaps.maps.compute.sweep",
    "MapStructure": "impactmaps.maps.family.structures",
    "classify": "impactmaps.maps.family.regimes",
    "lookup": "impactmaps.cases.case_lookup",
    "design_formula": "impactmaps.maps.read.lookup",
    "make_chart": "impactmaps.plotting.chart",
    # cases
    "load_case": "impactmaps.cases",
    "parse_case": "impactmaps.cases",
    "run_case": "impactmaps.cases",
    "Case": "impactmaps.cases",
    # any-law asymptotes, Hertz similarity, model validity
    "asymptote": "impactmaps.closed_forms.law_asymptotes",
    "AsymptoteResult": "impactmaps.closed_forms.law_asymptotes",
    "hertz_numbers": "impactmaps.closed_forms.hertz_similarity",
    "realise_hertz": "impactmaps.closed_forms.hertz_similarity",
    "validity_warnings": "impactmaps.validity",
    "ModelValidityWarning": "impactmaps._checks",
    "warn_if_invalid": "impactmaps.validity",
    # accuracy of map points
    "AccuracyControl": "impactmaps.maps.family.accuracy",
}

__all__ = ["__version__", *_EXPORTS]


def __getattr__(name: str):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module 'impactmaps' has no attribute {name!r}")
    value = getattr(importlib.import_module(module), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(__all__)
