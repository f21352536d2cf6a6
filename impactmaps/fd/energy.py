"""The energy ledger of the finite-difference beam.

Discrete kinetic, elastic and plastic energies of the beam and the law's contact
energies; the ledger closes to O(Δt²) (docs/fd_beam.rst).
"""

from __future__ import annotations

import numba
import numpy as np

from ..contact.base import KERNEL_TYPE, ContactLaw

__all__ = ["beam_energies", "contact_energies", "impact_ledger", "kernel_curve", "kinetic_energy"]

_VEC = numba.types.Array(numba.types.float64, 1, "C")


@numba.njit(numba.types.UniTuple(_VEC, 2)(KERNEL_TYPE, _VEC, _VEC, _VEC), cache=True)
def kernel_curve(kernel, params, alpha, alpha_max):
    """Force [N] and tangent stiffness [N/m] of a kernel along (α, α_max) pairs [m]."""
    force = np.empty(alpha.shape[0])
    stiffness = np.empty(alpha.shape[0])
    for i in range(alpha.shape[0]):
        force[i], stiffness[i] = kernel(alpha[i], alpha_max[i], params)
    return force, stiffness


def kinetic_energy(grid, v) -> float:
    """½ vᵀ M_mass v [J] of nodal velocities ``v`` [m/s]."""
    mv = grid.mass_diag * v
    mv[:-1] += grid.mass_off * v[1:]
    mv[1:] += grid.mass_off * v[:-1]
    return 0.5 * float(v @ mv)


def beam_energies(grid, result, v) -> dict:
    """Beam kinetic and elastic energy and plastic work [J] at t_{N−½} from the loop's result
    and final half-step velocities ``v`` [m/s]."""
    before_last = result.plastic_work - result.last_plastic_increment
    plastic = before_last + 0.5 * result.last_plastic_increment
    internal = result.elastic_energy_before_last + before_last + result.half_step_work
    return dict(beam_kinetic_energy=kinetic_energy(grid, v),
                beam_elastic_energy=internal - plastic,
                beam_plastic_work=plastic)


def _unloading_work(law: ContactLaw, params, low, high, alpha_max, points=20001) -> float:
    """∫ F dα [J] from ``low`` to ``high`` on the unloading curve from ``alpha_max`` (trapezoid)."""
    if high <= low:
        return 0.0
    alpha = np.linspace(low, high, points)
    alpha[0] = max(low, 1e-12 * high)  # the kernels return 0 at α = 0 exactly (no tension)
    force, _k = kernel_curve(law.kernel, params, alpha, np.full(points, float(alpha_max)))
    return float(np.trapezoid(force, alpha))


def contact_energies(law: ContactLaw, alpha_max, alpha_now=None) -> dict:
    """Contact energies at ``alpha_max`` [m]: ``permanent_indentation`` [m], ``dissipation`` [J]
    and ``stored`` [J] (recoverable from ``alpha_now``)."""
    if alpha_max <= 0.0:
        return dict(permanent_indentation=0.0, dissipation=0.0, stored=0.0)
    floor = float(law.permanent_indentation(alpha_max))
    stored = 0.0
    if alpha_now is not None and alpha_now > floor:
        params = np.ascontiguousarray(np.asarray(law.kernel_parameters, dtype=float))
        stored = _unloading_work(law, params, floor, min(alpha_now, alpha_max), alpha_max)
    return dict(permanent_indentation=floor, dissipation=float(law.dissipated_energy(alpha_max)),
                stored=stored)


def impact_ledger(law: ContactLaw, grid, result, v, impactor_mass, velocity,
                  separation_velocity):
    """The energy ledger [J] of an impact run (:class:`~impactmaps.fd.impact.FDDetails`) and
    :func:`contact_energies`, from the final velocities ``v`` [m/s], m [kg], V0 and the
    ``separation_velocity`` [m/s]."""
    impact_energy = 0.5 * impactor_mass * velocity**2
    contact = contact_energies(law, result.alpha_max,
                               result.final_alpha if result.in_contact else None)
    dissipation, stored = contact["dissipation"], contact["stored"]
    energy = dict(
        impact_kinetic_energy=impact_energy,
        gravity_work=float(result.gravity_work),
        impactor_kinetic_energy=0.5 * impactor_mass * result.impactor_velocity_half ** 2,
        rebound_kinetic_energy=(0.5 * impactor_mass * separation_velocity**2
                                if np.isfinite(separation_velocity) else np.nan),
        **beam_energies(grid, result, v),
        contact_dissipation=dissipation,
        contact_stored_energy=stored,
        damping_work=float(result.damping_work),
        contact_work_discrete=float(result.contact_work_sphere - result.contact_work_beam),
    )
    total = (energy["impactor_kinetic_energy"] + energy["beam_kinetic_energy"]
             + energy["beam_elastic_energy"] + energy["beam_plastic_work"]
             + dissipation + stored + energy["damping_work"])
    energy["energy_balance_error"] = (total - impact_energy - energy["gravity_work"]) / impact_energy
    return energy, contact
