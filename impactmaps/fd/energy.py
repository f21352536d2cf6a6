"""The energy ledger of the finite-difference beam.

With half-step kinetic energies the central-difference scheme (:mod:`impactmaps.fd._loop`)
satisfies a discrete energy identity exactly, the strain-energy/plastic-work split of the
section is exact (trapezoidal plastic work, :mod:`impactmaps.fd.section`), and the contact
energies are the law's own (``law.dissipated_energy``, ``law.permanent_indentation`` at
its ``α_max``). The ledger therefore closes up to the O(Δt²) difference between the
discrete contact work ``Σ F^n (α^{n+1} − α^{n−1})/2`` (kept as the diagnostic
``contact_work_discrete``) and the law's ``∫F dα`` — 1e-6 … 4e-5 of the impact energy in
the tests (roundoff without contact). It is a genuine check: a support stencil
inconsistent with the energy, or a wrong internal-force sign, breaks it.
"""

from __future__ import annotations

import numba
import numpy as np

from ..contact.base import KERNEL_TYPE, ContactLaw

__all__ = ["beam_energies", "contact_energies", "impact_ledger", "kernel_curve", "kinetic_energy"]

_VEC = numba.types.Array(numba.types.float64, 1, "C")


@numba.njit(numba.types.UniTuple(_VEC, 2)(KERNEL_TYPE, _VEC, _VEC, _VEC), cache=True)
def kernel_curve(kernel, params, alpha, alpha_max):
    """Force and tangent stiffness of a kernel along (α, α_max) pairs (function-pointer
    version of :func:`impactmaps.contact.evaluate_kernel`, compiled once for all laws)."""
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
    """Beam kinetic and elastic energy and plastic work [J] at the end of a run.

    ``result`` is the loop's :class:`~impactmaps.fd._loop.LoopResult`, ``v`` the final
    half-step velocities. The plastic work is taken through step N−1 plus half of the last
    increment (the ledger is taken at t_{N−½}); the elastic energy is the exact discrete
    internal work ``Σ f_int^n·(w^{n+1} − w^{n−1})/2`` minus that plastic work.
    """
    before_last = result.plastic_work - result.last_plastic_increment
    plastic = before_last + 0.5 * result.last_plastic_increment
    internal = result.elastic_energy_before_last + before_last + result.half_step_work
    return dict(beam_kinetic_energy=kinetic_energy(grid, v),
                beam_elastic_energy=internal - plastic,
                beam_plastic_work=plastic)


def _unloading_work(law: ContactLaw, params, low, high, alpha_max, points=20001) -> float:
    """∫ F dα [J] from ``low`` to ``high`` on the unloading curve leaving ``alpha_max``
    (trapezoidal rule on the kernel, ``points`` nodes)."""
    if high <= low:
        return 0.0
    alpha = np.linspace(low, high, points)
    alpha[0] = max(low, 1e-12 * high)  # the kernels return 0 at α = 0 exactly (no tension)
    force, _k = kernel_curve(law.kernel, params, alpha, np.full(points, float(alpha_max)))
    return float(np.trapezoid(force, alpha))


def contact_energies(law: ContactLaw, alpha_max, alpha_now=None) -> dict:
    """Contact-zone energies at the law's history ``alpha_max`` [m].

    Returns ``permanent_indentation`` α_f = ``law.permanent_indentation(α_max)`` [m],
    ``dissipation`` = ``law.dissipated_energy(α_max)`` [J] (loading work minus the work
    recovered unloading to α_f) and ``stored`` [J], the work recoverable from the current
    indentation ``alpha_now`` on the unloading curve (0 when separated; integrated from the
    kernel, 20001-point trapezoid).
    """
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
    """The energy ledger of an impact run [J] and the contact energies.

    Parameters
    ----------
    law : ContactLaw
        The contact law of the run.
    grid : impactmaps.fd.grid.Grid
        The beam's grid.
    result : LoopResult
        The loop's scalars.
    v : ndarray
        Final half-step nodal velocities [m/s].
    impactor_mass, velocity : float
        m [kg], V0 [m/s].
    separation_velocity : float
        Sphere velocity at the last separation [m/s] (nan if none).

    Returns
    -------
    energy : dict
        The ledger described in :class:`~impactmaps.fd.impact.FDDetails`.
    contact : dict
        :func:`contact_energies` at the run's α_max.
    """
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
