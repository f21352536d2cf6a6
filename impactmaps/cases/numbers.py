"""The normalised numbers of a case in the vocabulary of its contact law's maps.

A number printed for a case (``zeta``, ``lambda``, ``beta``, ``fmax_normalised``) means
what the maps of its law mean, so ``simulate`` and ``lookup`` agree: linear (ζ, λ, ω),
Hertz (ζ_h, λ_h, F_hs), plastic (β, ζ and λ at K_y), else the linearised numbers
(docs/output_keys.rst).
"""

from __future__ import annotations

import math

from ..contact.sphere import law_for_sphere
from ..contact.contact_scale import reference_contact_stiffness
from .case import Case

__all__ = ["case_dimensionless", "case_numbers", "NUMBER_BASES"]

#: What ``lambda_basis`` says for the Hertz and plastic vocabularies (linear: the basis of
#: :func:`case_dimensionless`).
NUMBER_BASES = {
    "hertz": "Hertz numbers: ζ_h = ζ(m, K_eq), λ_h = K_st/K_eq, F/F_hs, K_eq = m V0²/α_m² (as lookup --law hertz)",
    "plastic": "linearised stiffness K_y = 1.5 K_h sqrt(α_y): β, ζ(m, K_y), λ = K_st/K_y, F/(m V0 ω_y) "
               "(as lookup --law yc|stronge)",
}


def case_dimensionless(case: Case) -> dict:
    """The linearised dimensionless numbers of a case (which K: docs/output_keys.rst):
    ``beta``, ``lambda``, ``zeta`` [-] or ``None``, ``lambda_basis``,
    ``contact_stiffness_N_m``, ``reference_contact_stiffness_N_m``, ``static_stiffness_N_m``
    (``None`` for a half-space), ``impactor_mass_kg``, ``velocity_m_s``.
    """
    mass, velocity, law = case.impactor_mass, case.velocity, case.law
    reference = float(reference_contact_stiffness(law, mass, velocity))
    if law.linear_stiffness is not None:
        stiffness, basis = float(law.linear_stiffness), "linear law stiffness K"
    else:
        stiffness, basis = reference, "solver reference stiffness (loading tangent at the half-space peak indentation)"
        linear_options = {k: v for k, v in case.contact_options.items()
                          if k in ("target_radius", "yield_strength")}
        try:
            linear = law_for_sphere("linear", case.sphere, case.target_material, **linear_options)
        except ValueError:
            pass  # no yield strength known: keep the reference stiffness
        else:
            stiffness, basis = float(linear.linear_stiffness), "linearised contact stiffness K_y (Christoforou & Yigit 1998, eqs 9, 10)"
    beta = law.impact_number(mass, velocity)
    if case.target_type == "halfspace":
        static = lam = zeta = None
    else:
        static = float(case.target.static_stiffness())
        lam = static / stiffness
        zeta = float(case.target.loss_factor(mass, stiffness))
    return {
        "beta": None if beta is None else float(beta),
        "lambda": lam,
        "zeta": zeta,
        "lambda_basis": basis,
        "contact_stiffness_N_m": stiffness,
        "reference_contact_stiffness_N_m": reference,
        "static_stiffness_N_m": static,
        "impactor_mass_kg": mass,
        "velocity_m_s": velocity,
    }


def _plastic(case: Case):
    """``plastic_numbers`` of the case, or None when its law is not a plastic map law."""
    try:
        from ..maps.compute.plastic_points import plastic_numbers
        from ..maps.family.builtin_families import plastic_law_of

        plastic_law_of(case.law)
    except (ImportError, ValueError):
        return None
    return plastic_numbers(case.target, case.law, case.impactor_mass, case.velocity)


def case_numbers(case: Case) -> dict:
    """The normalised numbers of ``case`` under the names its law's maps use: ``vocabulary``
    (``"linear"``, ``"hertz"``, ``"plastic"``, ``"linearised"``), ``beta``, ``zeta``,
    ``lambda`` [-] (``None`` where undefined), ``lambda_basis``, ``force_scale_N``,
    ``time_scale_s``, ``contact_stiffness_N_m``, a Hertz case's linearised numbers and the
    other keys of :func:`case_dimensionless` (docs/output_keys.rst).
    """
    linear = case_dimensionless(case)
    mass, velocity = case.impactor_mass, case.velocity
    numbers = dict(linear)
    halfspace = case.target_type == "halfspace"
    if case.law.linear_stiffness is not None:
        omega = math.sqrt(linear["contact_stiffness_N_m"] / mass)
        return numbers | {"vocabulary": "linear", "force_scale_N": mass * velocity * omega, "time_scale_s": 1.0 / omega}
    if case.law.hertzian_stiffness is not None:
        from ..closed_forms.halfspace import hertz_max_indentation

        stiffness = float(case.law.hertzian_stiffness)
        alpha_m = float(hertz_max_indentation(mass, velocity, stiffness))
        numbers |= {"vocabulary": "hertz", "lambda_basis": NUMBER_BASES["hertz"],
                    "force_scale_N": stiffness * alpha_m**1.5,
                    "time_scale_s": alpha_m / velocity, "zeta": None, "lambda": None,
                    "zeta_linearised": linear["zeta"], "lambda_linearised": linear["lambda"],
                    "linearised_basis": linear["lambda_basis"]}
        if not halfspace:
            from ..closed_forms.hertz_similarity import hertz_numbers

            hertz = hertz_numbers(case.target, case.law, mass, velocity)
            numbers |= {"zeta": hertz.loss_factor, "lambda": hertz.relative_stiffness}
        return numbers
    plastic = None if halfspace else _plastic(case)
    if plastic is not None:
        return numbers | {"vocabulary": "plastic", "lambda_basis": NUMBER_BASES["plastic"],
                          "beta": plastic.impact_number, "zeta": plastic.loss_factor,
                          "lambda": plastic.relative_stiffness,
                          "contact_stiffness_N_m": plastic.linearised_stiffness,
                          "force_scale_N": plastic.force_scale, "time_scale_s": plastic.time_scale}
    omega = math.sqrt(linear["contact_stiffness_N_m"] / mass)
    return numbers | {"vocabulary": "linearised", "force_scale_N": mass * velocity * omega,
                      "time_scale_s": 1.0 / omega}
