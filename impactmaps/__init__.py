"""impactmaps — low-velocity impact of a sphere on beams and plates.

Force histories for physical cases, the dimensionless (β, λ, ζ) picture of
Christoforou & Yigit (1998), the normalised maximum-force maps, regimes and design
lookups, all verified against exact solutions.

The public API is re-exported here lazily (importing ``impactmaps`` stays cheap; each
name loads its module on first use)::

    import impactmaps
    impactmaps.restitution(10.0)                     # e(β), Yigit–Christoforou law
    impactmaps.lookup(1.198, 0.425, kind="plate", theory="kirchhoff")
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
    "ImpactResult": "impactmaps.solvers.result",
    "halfspace_impact": "impactmaps.solvers.halfspace",
    "restitution": "impactmaps.solvers.halfspace",
    "simulate_fd": "impactmaps.fd",
    "FDBeam": "impactmaps.fd",
    # targets, materials, contact
    "Beam": "impactmaps.targets.beam",
    "Plate": "impactmaps.targets.plate",
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
    "sweep": "impactmaps.maps.sweep",
    "MapStructure": "impactmaps.maps.structures",
    "classify": "impactmaps.maps.regimes",
    "lookup": "impactmaps.maps.lookup",
    "lookup_plastic": "impactmaps.maps.plastic_lookup",
    "design_formula": "impactmaps.maps.lookup",
    "make_chart": "impactmaps.maps.chart",
    # cases
    "load_case": "impactmaps.cases",
    "parse_case": "impactmaps.cases",
    "run_case": "impactmaps.cases",
    "Case": "impactmaps.cases",
    # any-law asymptotes, Hertz similarity, model validity
    "asymptote": "impactmaps.law_asymptotes",
    "AsymptoteResult": "impactmaps.law_asymptotes",
    "hertz_numbers": "impactmaps.hertz_similarity",
    "realise_hertz": "impactmaps.hertz_similarity",
    "validity_warnings": "impactmaps.validity",
    "warn_if_invalid": "impactmaps.validity",
    # accuracy of map points
    "AccuracyControl": "impactmaps.maps.accuracy",
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
