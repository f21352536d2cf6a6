"""Case files: a physical impact described in TOML, built into impactmaps objects.

A case file describes one impact of a sphere on a beam, a plate or a half-space, in SI
units. It is parsed with the standard-library :mod:`tomllib` and validated key by key:
every error is a ``ValueError`` that names the key path (``target.length``), the value
and the valid range; an unknown key is an error that lists the allowed keys, so typos
cannot pass silently.

Format
------
::

    name = "steel plate, Hertz"          # optional label (default: the file name)
    description = "..."                  # optional free text

    [impactor]
    radius = 0.005                       # sphere radius R [m]
    material = "structural-steel"        # catalogue name, or an inline table
    # mass = 0.004                       # [kg]; default: solid sphere ρ (4/3) π R³
    # density = 7800.0                   # [kg/m³]; overrides the material's (not with mass)
    velocity = 2.0                       # approach velocity V0 [m/s]

    [target]
    type = "plate"                       # "beam" | "plate" | "halfspace"
    # beam:      length, width, height [m]; supports ("ss", "cc", "cs", "cf", "ff");
    #            theory ("euler", "rayleigh", "timoshenko"); impact_position x0 [m]
    # plate:     length_x, length_y, thickness [m]; edges ("SSSS", "CCCC", ...);
    #            theory ("kirchhoff", "mindlin"); impact_point [x0, y0] [m]
    # both:      shear_correction [-]; damping_ratio [-] (plates)
    material = "structural-steel"        # catalogue name or inline isotropic table, or
    # plies = [{material = "t300-934", angle_deg = 0.0, thickness = 0.000125}, ...]
    # layup = {ply = "t300-934", angles_deg = [0, 90], symmetric = true, ply_thickness = 0.000125}
    # yield_strength = 1.0e9             # laminate strength S_y [Pa] (with plies/layup only)

    [contact]
    law = "hertz"                        # a registered law: hertz, linear, yigit-christoforou, stronge
    # options: target_radius [m]; yield_strength [Pa] (not hertz); stiffness (hertz
    # K_h [N/m^1.5] or linear K [N/m], overriding the value built from the materials);
    # stronge: yield_pressure_factor, plastic_pressure_factor, plastic_indentation_ratio

    [solver]                             # optional
    # kind = "modal"                     # "modal" (default) or "fd" (finite-difference beam)
    # duration [s] (time limit; required by "fd"); time_step [s] (forced step, modal)
    # modal: the fields of ModalSettings — cutoff_ratio, min_modes, residual_flexibility,
    #        time_step_ratio, resolve_ratio, force_resolution, max_time_ratio (not with
    #        duration), max_events, check_convergence, tolerance

    [output]                             # optional
    # history_stride = 1                 # write every n-th history row
    # normalised = false                 # also write the normalised history

    [fd]                                 # optional, finite-difference beam (kind = "fd")
    # n_elements, n_half_layers, plastic, hardening_modulus [Pa],
    # damping_per_length [N s/m²], width_constraint, gravity, safety_factor, time_step [s],
    # history_stride, gauge_positions [m]

Material tables: see :mod:`impactmaps.cases._materials`.

Each table maps onto a constructor and its keys are that constructor's options, so
the defaults (and ranges) of the target theory, supports and impact point are those of
the target classes (:meth:`impactmaps.targets.beams.beam.Beam.rectangular`,
:meth:`impactmaps.targets.plates.plate.Plate.isotropic`), of the contact law
(:func:`impactmaps.contact.law_options`) and of
:class:`impactmaps.solvers.modal.ModalSettings`. ``[solver] kind = "fd"`` (or
``impactmaps fd CASE.toml``) runs the finite-difference Rayleigh beam: the target must
be an isotropic beam whose material has a yield strength; without ``[contact]`` the
law is seed 000's refined Stronge law.

Dimensionless numbers of a case (:func:`case_dimensionless`)
------------------------------------------------------------
* ``beta`` — the impact number ``β = V0/(ω_h α_y)`` (seed 001 eqs 9, 11, 12), reported
  for the elastic-plastic laws only (``yigit-christoforou``; for ``stronge`` with
  ``α_y`` from seed 001 eq 9 and the law's E*, R and yield strength — *not* Stronge's
  own yield indentation δ_y); ``None`` for ``hertz`` and ``linear``.
* ``lambda`` — ``K_st/K``. ``K`` is chosen, in this order, as: the stiffness of a
  ``linear`` law; else the linearised contact stiffness ``K_y = 1.5 K_h sqrt(α_y)``
  (seed 001 eqs 9, 10, 18) of the sphere/target pair when a yield strength is known
  (from either material or ``contact.yield_strength``); else the reference stiffness
  the modal solver uses to set the contact frequency (tangent stiffness of the law on
  its loading curve at the half-space peak indentation,
  :func:`impactmaps.solvers.modal.reference_contact_stiffness`). The summary says
  which (``lambda_basis``). ``None`` for a half-space (``K_st`` infinite).
* ``zeta`` — the target's own loss factor ``target.loss_factor(m_i, K)`` with the same
  ``K`` (plate: seed 001 eq 34; beam: the corrected eq 38, docs/physics_contract.md §1). ``None`` for
  a half-space.

These are the *linearised* numbers. A run's summary (and ``impactmaps check``) reports
the numbers in the vocabulary of the law's maps instead (:func:`case_numbers`: the Hertz
numbers ζ_h, λ_h and F/F_hs for a Hertz law, with the linearised ones as
``zeta_linearised``, ``lambda_linearised``), as ``impactmaps lookup`` prints them;
``docs/output_keys.rst`` has the table of keys per law.

Outputs (:func:`write_case_outputs`): ``history.csv`` (``time_s, force_N,
indentation_m, impactor_displacement_m, impactor_velocity_m_s, target_displacement_m,
target_velocity_m_s`` and the solver's extras — displacements positive into the target,
the target deflection taken at the impact point), ``summary.json`` and a copy of the
case file ``case.toml``.
"""

from __future__ import annotations

from .case import (
    SOLVER_KINDS,
    TARGET_TYPES,
    Case,
    OutputSettings,
    load_case,
    parse_case,
)
from .numbers import case_dimensionless, case_numbers
from .run import (
    case_summary,
    read_case_outputs,
    run_case,
    write_case_outputs,
)

__all__ = [
    "Case",
    "OutputSettings",
    "SOLVER_KINDS",
    "TARGET_TYPES",
    "load_case",
    "parse_case",
    "run_case",
    "case_dimensionless",
    "case_numbers",
    "case_summary",
    "write_case_outputs",
    "read_case_outputs",
]
