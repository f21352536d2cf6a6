"""The compiled time loop of the finite-difference beam (numba; private numerics).

Central differences in velocity form with one factorised tridiagonal solve per step; the
contact kernel is passed as a function pointer (``KERNEL_TYPE``), so one compiled loop
serves every law. :func:`run_loop` allocates state and records. Scheme: docs/fd_beam.rst.
"""

from __future__ import annotations

import warnings
from collections import namedtuple

import numba
import numpy as np

from ..contact.base import KERNEL_TYPE
from ..solvers.integrator._peak import parabolic_peak
from .grid import factorise
from .section import return_map

__all__ = ["Drive", "LoopResult", "run_loop"]

#: Contact intervals kept at most (later ones are counted, not stored).
MAX_INTERVALS = 10_000

#: Grid operators as the loop needs them (``pivots``, ``lower``: LDLᵀ factors of
#: M_mass + ½Δt C_d with the constrained rows as identity).
LoopGrid = namedtuple("LoopGrid", "dx constrained section_weight stencil mass_diag mass_off "
                      "damping_diag pivots lower")
#: The section's constants: layer mid-planes z, layer area b Δz, E, σ_y, H, model EI and the
#: width constraint's β_sat, γ (:mod:`impactmaps.fd.wide_section`).
LoopSection = namedtuple("LoopSection", "plastic z layer_area youngs_modulus yield_strength "
                         "hardening_modulus bending_stiffness constraint_saturation "
                         "constraint_rate")
#: Per node (and layer) section state, updated in place (``constraint``: β_c, part of ``back``).
LayerState = namedtuple("LayerState", "stress back plastic_strain plastic_work_node virgin "
                        "constraint")
#: What drives the beam: a sphere (``has_impactor``) and/or a prescribed load history
#: ``external_force`` (one value per step, or empty), both at ``node``.
Drive = namedtuple("Drive", "has_impactor impactor_mass velocity gravity node external_force")
#: Time step [s], number of steps, record every ``stride``-th step.
Stepping = namedtuple("Stepping", "dt n_steps stride")
#: Output arrays filled in place: histories at step n, gauge interpolation, contact intervals.
Records = namedtuple("Records", "time force alpha u vs wk vk gauge_left gauge_weight gauge_w "
                     "gauge_k intervals")
#: The loop's scalars (see :func:`run_loop`) and the final curvature of every node.
LoopResult = namedtuple("LoopResult", "alpha_max peak_force peak_time n_intervals "
                        "separation_velocity in_contact impactor_velocity_half damping_work "
                        "contact_work_beam contact_work_sphere gravity_work plastic_work "
                        "last_plastic_increment elastic_energy_before_last half_step_work "
                        "records final_alpha curvature")

_F8 = numba.types.float64
_I8 = numba.types.int64
_BOOL = numba.types.boolean
_VEC = numba.types.Array(_F8, 1, "C")
_MAT = numba.types.Array(_F8, 2, "C")
_BOOL_VEC = numba.types.Array(_BOOL, 1, "C")
_GRID_TYPE = numba.types.NamedTuple((_F8, _BOOL_VEC, _VEC, _MAT, _VEC, _VEC, _VEC, _VEC, _VEC),
                                    LoopGrid)
_SECTION_TYPE = numba.types.NamedTuple((_BOOL, _VEC, _F8, _F8, _F8, _F8, _F8, _F8, _F8),
                                       LoopSection)
_LAYERS_TYPE = numba.types.NamedTuple((_MAT, _MAT, _MAT, _VEC, _BOOL_VEC, _MAT), LayerState)
_DRIVE_TYPE = numba.types.NamedTuple((_BOOL, _F8, _F8, _F8, _I8, _VEC), Drive)
_STEPPING_TYPE = numba.types.NamedTuple((_F8, _I8, _I8), Stepping)
_RECORDS_TYPE = numba.types.NamedTuple(
    (_VEC, _VEC, _VEC, _VEC, _VEC, _VEC, _VEC, numba.types.Array(_I8, 1, "C"), _VEC, _MAT,
     _MAT, _MAT), Records)
_RESULT_TYPE = numba.types.NamedTuple(
    (_F8, _F8, _F8, _I8, _F8, _BOOL, _F8, _F8, _F8, _F8, _F8, _F8, _F8, _F8, _F8, _I8, _F8,
     _VEC), LoopResult)
_INTEGRATE_SIGNATURE = _RESULT_TYPE(KERNEL_TYPE, _VEC, _GRID_TYPE, _SECTION_TYPE, _LAYERS_TYPE,
                                    _DRIVE_TYPE, _STEPPING_TYPE, _VEC, _VEC, _RECORDS_TYPE)


# =====================================================================================
# Section: curvatures, moments, energies
# =====================================================================================
@numba.njit(cache=True, inline="always")
def _curvatures(w, stencil, inv_dx2, out):
    n = w.shape[0]
    for j in range(n):
        value = stencil[1, j] * w[j]
        if j > 0:
            value += stencil[0, j] * w[j - 1]
        if j < n - 1:
            value += stencil[2, j] * w[j + 1]
        out[j] = value * inv_dx2


@numba.njit(cache=True, inline="always")
def _section_moments(section, layers, section_weight, curvature, old_curvature, moment):
    """Update every node's section to the new curvature; return Σ c_j ΔW_p,j [J/m].

    Never-yielded nodes stay on an elastic fast path until they yield.
    """
    z = section.z
    youngs_modulus = section.youngs_modulus
    bending_stiffness = section.bending_stiffness
    layer_area = section.layer_area
    stress, back, virgin = layers.stress, layers.back, layers.virgin
    total_work = 0.0
    n_layers = z.shape[0]
    outer = abs(z[0])
    for j in range(curvature.shape[0]):
        if section_weight[j] == 0.0:
            moment[j] = 0.0
            continue
        if not section.plastic:
            moment[j] = -bending_stiffness * curvature[j]
            continue
        if virgin[j]:
            if youngs_modulus * outer * abs(curvature[j]) <= section.yield_strength:
                moment[j] = -bending_stiffness * curvature[j]
                continue
            virgin[j] = False
            for i in range(n_layers):
                stress[j, i] = -youngs_modulus * z[i] * old_curvature[j]
        dk = curvature[j] - old_curvature[j]
        m = 0.0
        work = 0.0
        for i in range(n_layers):
            s, b, c, p, wk = return_map(stress[j, i], back[j, i], layers.constraint[j, i],
                                        -z[i] * dk, youngs_modulus, section.yield_strength,
                                        section.hardening_modulus,
                                        section.constraint_saturation, section.constraint_rate)
            stress[j, i] = s
            back[j, i] = b
            layers.constraint[j, i] = c
            layers.plastic_strain[j, i] += p
            m += s * z[i]
            work += wk
        moment[j] = m * layer_area
        layers.plastic_work_node[j] += work * layer_area
        total_work += section_weight[j] * work * layer_area
    return total_work


@numba.njit(cache=True, inline="always")
def _materialise(section, layers, curvature):
    """Write the layer stresses of never-yielded nodes, σ_i = −E z_i κ."""
    if not section.plastic:
        return
    z = section.z
    for j in range(curvature.shape[0]):
        if layers.virgin[j]:
            for i in range(z.shape[0]):
                layers.stress[j, i] = -section.youngs_modulus * z[i] * curvature[j]


@numba.njit(cache=True, inline="always")
def _elastic_energy(section, layers, section_weight, curvature, dx):
    """Strain energy Σ c_j Δx u(κ_j) [J]: layers' σ²/(2E), or ½ EI κ² for the elastic model."""
    stress = layers.stress
    total = 0.0
    for j in range(curvature.shape[0]):
        if section_weight[j] == 0.0:
            continue
        if section.plastic:
            s2 = 0.0
            for i in range(stress.shape[1]):
                s2 += stress[j, i] * stress[j, i]
            total += section_weight[j] * dx * section.layer_area * s2 / (2.0 * section.youngs_modulus)
        else:
            total += section_weight[j] * dx * 0.5 * section.bending_stiffness * curvature[j] ** 2
    return total


# =====================================================================================
# Beam: internal forces and the velocity update
# =====================================================================================
@numba.njit(cache=True, inline="always")
def _internal_forces(grid, moment, out):
    """f_int = −Bᵀ(c Δx M)/Δx² [N]: the moments' nodal forces."""
    n = out.shape[0]
    stencil = grid.stencil
    for j in range(n):
        out[j] = 0.0
    for j in range(n):
        q = grid.section_weight[j] * moment[j] / grid.dx
        if q == 0.0:
            continue
        if j > 0:
            out[j - 1] -= q * stencil[0, j]
        out[j] -= q * stencil[1, j]
        if j < n - 1:
            out[j + 1] -= q * stencil[2, j]


@numba.njit(cache=True, inline="always")
def _new_velocity(grid, dt, v, internal_force, node, load, rhs, v_new):
    """Solve ``(M + ½Δt C) v_new = (M − ½Δt C) v + Δt (f_ext − f_int)`` (LDLᵀ factors)."""
    n = v.shape[0]
    for j in range(n):
        if grid.constrained[j]:
            rhs[j] = 0.0
            continue
        value = (grid.mass_diag[j] - 0.5 * dt * grid.damping_diag[j]) * v[j]
        if j > 0:
            value += grid.mass_off[j - 1] * v[j - 1]
        if j < n - 1:
            value += grid.mass_off[j] * v[j + 1]
        value -= dt * internal_force[j]
        if j == node:
            value += dt * load
        rhs[j] = value
    lower, pivots = grid.lower, grid.pivots
    for j in range(1, n):
        rhs[j] -= lower[j] * rhs[j - 1]
    v_new[n - 1] = rhs[n - 1] / pivots[n - 1]
    for j in range(n - 2, -1, -1):
        v_new[j] = rhs[j] / pivots[j] - lower[j + 1] * v_new[j + 1]


@numba.njit(cache=True, inline="always")
def _add_damping_work(damping_work, grid, dt, v, v_new):
    """The damping work of one step, Δt Σ C_j (v_mid)², added to the running total [J]."""
    for j in range(v.shape[0]):
        vm = 0.5 * (v[j] + v_new[j])
        damping_work += dt * grid.damping_diag[j] * vm * vm
    return damping_work


# =====================================================================================
# Records and contact intervals
# =====================================================================================
@numba.njit(cache=True, inline="always")
def _track_contact(force, in_contact, n_intervals, t, intervals):
    """Open or close a contact interval at ``t``; returns (in_contact, n_intervals, separated)."""
    if force > 0.0 and not in_contact:
        if n_intervals < intervals.shape[0]:
            intervals[n_intervals, 0] = t
            intervals[n_intervals, 1] = np.nan
        return True, n_intervals + 1, False
    if force <= 0.0 and in_contact:
        if n_intervals <= intervals.shape[0]:
            intervals[n_intervals - 1, 1] = t
        return False, n_intervals, True
    return in_contact, n_intervals, False


@numba.njit(cache=True, inline="always")
def _record(records, index, t, force, alpha, u, vs, w, vk, node, curvature):
    """Write step ``index`` of the histories (and the gauges' deflection and curvature)."""
    records.time[index] = t
    records.force[index] = force
    records.alpha[index] = alpha
    records.u[index] = u
    records.vs[index] = vs
    records.wk[index] = w[node]
    records.vk[index] = vk
    for g in range(records.gauge_left.shape[0]):
        i = records.gauge_left[g]
        th = records.gauge_weight[g]
        records.gauge_w[index, g] = (1.0 - th) * w[i] + th * w[i + 1]
        records.gauge_k[index, g] = (1.0 - th) * curvature[i] + th * curvature[i + 1]


@numba.njit(cache=True, inline="always")
def _close_ledger(grid, section, layers, w, curvature, moment, new_curvature):
    """Internal work of the last half step: (elastic energy before it, half-step work,
    last plastic increment); advances the section to ``w``."""
    n = w.shape[0]
    dx = grid.dx
    _materialise(section, layers, curvature)
    elastic_before = _elastic_energy(section, layers, grid.section_weight, curvature, dx)
    _curvatures(w, grid.stencil, 1.0 / (dx * dx), new_curvature)
    half_work = 0.0
    for j in range(n):
        half_work += 0.5 * grid.section_weight[j] * dx * (-moment[j]) * (new_curvature[j] - curvature[j])
    last_plastic = dx * _section_moments(section, layers, grid.section_weight, new_curvature,
                                         curvature, moment)
    for j in range(n):
        curvature[j] = new_curvature[j]
    _materialise(section, layers, curvature)
    return elastic_before, half_work, last_plastic


# =====================================================================================
# The time loop
# =====================================================================================
@numba.njit(_INTEGRATE_SIGNATURE, cache=True)
def _integrate(kernel, params, grid, section, layers, drive, stepping, w, v, records):
    """March ``stepping.n_steps`` steps from (w⁰, v^{−½}), updating ``w``, ``v``, ``layers``
    and ``records`` in place."""
    n = w.shape[0]
    dt, dx, node = stepping.dt, grid.dx, drive.node
    inv_dx2 = 1.0 / (dx * dx)
    curvature = np.zeros(n)
    new_curvature = np.zeros(n)
    moment = np.zeros(n)
    force_vector = np.zeros(n)
    rhs = np.zeros(n)
    v_new = np.zeros(n)
    has_impactor = drive.has_impactor
    has_load = drive.external_force.shape[0] > 0

    u = 0.0
    vs = drive.velocity - 0.5 * dt * drive.gravity  # v_s^{-1/2}
    alpha_max = peak_force = peak_time = 0.0
    in_contact = False
    n_intervals = 0
    separation_velocity = np.nan
    damping_work = contact_work_beam = contact_work_sphere = gravity_work = plastic_work = 0.0
    record = 0
    last_force = force_before_peak = force_after_peak = 0.0
    peak_step = -2

    for step in range(stepping.n_steps):
        t = step * dt
        # -- section: curvature and moments at w^n; internal forces ------------------
        _curvatures(w, grid.stencil, inv_dx2, new_curvature)
        plastic_work += dx * _section_moments(section, layers, grid.section_weight,
                                              new_curvature, curvature, moment)
        for j in range(n):
            curvature[j] = new_curvature[j]
        # -- contact force at α^n and its peak ----------------------------------------
        force = 0.0
        alpha = 0.0
        if has_impactor:
            alpha = u - w[node]
            force, _stiffness = kernel(alpha, alpha_max, params)
            if alpha > alpha_max:
                alpha_max = alpha
        load = force
        if has_load:
            load += drive.external_force[step]
        if force > peak_force:
            peak_force = force
            peak_time = t
            peak_step = step
            force_before_peak = last_force
        elif step == peak_step + 1:
            force_after_peak = force
        last_force = force
        # -- beam: v^{n+½} and the work accumulators (exact discrete identities) -------
        _internal_forces(grid, moment, force_vector)
        _new_velocity(grid, dt, v, force_vector, node, load, rhs, v_new)
        damping_work = _add_damping_work(damping_work, grid, dt, v, v_new)
        vk_mid = 0.5 * (v[node] + v_new[node])
        contact_work_beam += dt * load * vk_mid
        # -- sphere ---------------------------------------------------------------------
        vs_mid = vs
        if has_impactor:
            vs_new = vs + dt * (drive.gravity - force / drive.impactor_mass)
            vs_mid = 0.5 * (vs + vs_new)
            gravity_work += drive.impactor_mass * drive.gravity * dt * vs_mid
            contact_work_sphere += dt * force * vs_mid
            u += dt * vs_new
            vs = vs_new
        # -- contact intervals and the record at step n ---------------------------------
        in_contact, n_intervals, separated = _track_contact(force, in_contact, n_intervals, t,
                                                            records.intervals)
        if separated:
            separation_velocity = vs_mid
        if step % stepping.stride == 0 and record < records.time.shape[0]:
            _record(records, record, t, force if has_impactor else load, alpha,
                    u - dt * vs if has_impactor else 0.0, vs_mid, w, vk_mid, node, curvature)
            record += 1
        # -- advance --------------------------------------------------------------------
        for j in range(n):
            v[j] = v_new[j]
            w[j] += dt * v_new[j]

    elastic_before, half_work, last_plastic = _close_ledger(grid, section, layers, w, curvature,
                                                            moment, new_curvature)
    final_alpha = u - w[node] if has_impactor else 0.0
    if (peak_step >= 1 and peak_step + 1 < stepping.n_steps
            and force_before_peak > 0.0 and force_after_peak > 0.0):  # both neighbours in contact
        peak_force, offset = parabolic_peak(force_before_peak, peak_force, force_after_peak)
        peak_time += offset * dt
    return LoopResult(alpha_max, peak_force, peak_time, n_intervals, separation_velocity,
                      in_contact, vs, damping_work, contact_work_beam, contact_work_sphere,
                      gravity_work, plastic_work, last_plastic, elastic_before, half_work,
                      record, final_alpha, curvature)


# =====================================================================================
# Python side: allocate, call, trim
# =====================================================================================
def _loop_section(beam):
    section = beam.section
    return LoopSection(beam.plastic, np.ascontiguousarray(section.layer_positions, dtype=float),
                       float(section.width * section.layer_thickness),
                       float(beam.youngs_modulus), float(beam.yield_strength),
                       float(beam.hardening_modulus), float(beam.bending_stiffness),
                       float(section.constraint_saturation), float(section.constraint_rate))


def run_loop(beam, grid, kernel, params, drive: Drive, stepping: Stepping, w0, v0,
             gauge_left, gauge_weight):
    """Run the compiled loop on ``beam`` and its ``grid`` from ``w0`` [m] and ``v0`` (v^{−½}) [m/s].

    ``kernel``/``params``: the contact kernel and its parameters; ``drive``: sphere and/or
    prescribed load; ``stepping``: Δt [s], step count, stride; ``gauge_left``,
    ``gauge_weight``: :func:`impactmaps.fd.grid.gauge_weights`. Returns the
    :class:`LoopResult` and a dict of the final state and records [SI].
    """
    section = _loop_section(beam)
    n = grid.n_nodes
    shape = (n, section.z.shape[0]) if beam.plastic else (n, 1)
    layers = LayerState(np.zeros(shape), np.zeros(shape), np.zeros(shape), np.zeros(n),
                        np.ones(n, dtype=bool), np.zeros(shape))
    pivots, lower = factorise(grid, stepping.dt)
    loop_grid = LoopGrid(float(grid.dx), grid.constrained, grid.section_weight, grid.stencil,
                         grid.mass_diag, grid.mass_off, grid.damping_diag, pivots, lower)
    n_records = (stepping.n_steps - 1) // stepping.stride + 1
    n_gauges = gauge_left.size
    records = Records(*(np.zeros(n_records) for _ in range(7)), gauge_left, gauge_weight,
                      np.zeros((n_records, n_gauges)), np.zeros((n_records, n_gauges)),
                      np.full((MAX_INTERVALS, 2), np.nan))
    w = w0.copy()
    v = v0.copy()
    result = _integrate(kernel, params, loop_grid, section, layers, drive, stepping, w, v, records)
    if result.n_intervals > MAX_INTERVALS:
        warnings.warn(f"{result.n_intervals} contacts; only the first {MAX_INTERVALS} intervals "
                      "are kept", stacklevel=3)
    state = dict(w=w, v=v, stress=layers.stress, back=layers.back, constraint=layers.constraint,
                 plastic_strain=layers.plastic_strain,
                 plastic_work_node=layers.plastic_work_node, records=records,
                 intervals=records.intervals[: min(result.n_intervals, MAX_INTERVALS)])
    return result, state
