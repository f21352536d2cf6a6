"""Response of the finite-difference beam to a prescribed load: :func:`simulate_fd_response`."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .._checks import require_finite, require_positive
from ..contact.linear import LinearContact
from ._loop import Drive, Stepping, run_loop
from .beam import FDBeam, require_stride
from .energy import beam_energies, kinetic_energy
from .residual import residual_state
from .grid import (
    beam_grid,
    factorise,
    gauge_columns,
    gauge_weights,
    node_for,
    tridiagonal_solve,
)
from .timestep import choose_time_step

__all__ = ["FDResponse", "simulate_fd_response"]


@dataclass(frozen=True)
class FDResponse:
    """Response of an :class:`FDBeam` to a prescribed point load (no impactor).

    Attributes
    ----------
    history : pandas.DataFrame
        ``time_s, load_N, deflection_at_load_m, velocity_at_load_m_s`` and gauge columns.
    final_deflection : ndarray
        Nodal deflections at the end [m].
    energy : dict
        ``load_work, beam_kinetic_energy, beam_elastic_energy, beam_plastic_work,
        damping_work`` [J], ``energy_balance_error`` [-].
    time_step : float
        Δt [s].
    load_node_position : float
        Node carrying the load [m].
    residual : pandas.DataFrame or None
        Per-node residual state, as ``FDDetails.residual``; None without a step.
    """

    history: pd.DataFrame
    final_deflection: np.ndarray
    energy: dict
    time_step: float
    load_node_position: float
    residual: pd.DataFrame | None = None


def simulate_fd_response(beam: FDBeam, load=None, load_position=None, *, duration,
                         time_step=None, safety_factor=0.8, initial_deflection=None,
                         gauge_positions=(), history_stride=1) -> FDResponse:
    """Response of the beam to a prescribed nodal point load and/or initial deflection.

    Parameters
    ----------
    beam : FDBeam
        The beam.
    load : callable, optional
        Vectorised ``load(t) -> force [N]`` at the node nearest ``load_position`` [m]
        (default mid-span). Default: no load.
    duration : float
        Simulated time [s].
    time_step, safety_factor, gauge_positions, history_stride : optional
        As for :func:`~impactmaps.fd.simulate_fd`.
    initial_deflection : callable or array_like, optional
        ``w(x)`` [m] at t = 0 (callable or N_l + 1 values); the beam starts at rest.

    Returns
    -------
    FDResponse
    """
    if not isinstance(beam, FDBeam):
        raise ValueError(f"beam = {beam!r} is not an FDBeam")
    require_positive("duration", duration, "s")
    stride = require_stride(history_stride)
    grid = beam_grid(beam)
    _x_load, node = node_for(beam, grid, load_position, "load_position")
    _positions, gauge_left, gauge_weight = gauge_weights(beam, gauge_positions)
    dt, _limit = choose_time_step(grid, time_step, safety_factor, 0.0)
    n_steps = int(math.ceil(float(duration) / dt))
    times = np.arange(n_steps) * dt
    external = np.zeros(n_steps)
    if load is not None:
        external = np.array(np.broadcast_to(np.asarray(load(times), float), (n_steps,)))
        require_finite("load(t)", external, "N")
    n = grid.n_nodes
    w0 = np.zeros(n)
    if initial_deflection is not None:
        values = initial_deflection(beam.node_positions) if callable(initial_deflection) \
            else initial_deflection
        w0 = np.array(np.broadcast_to(np.asarray(values, float), (n,)))
        require_finite("initial_deflection", w0, "m")
        w0[grid.constrained] = 0.0
    # v^{-1/2} = −½Δt a⁰ with M a⁰ = f_ext⁰ − K w⁰ (elastic start; the beam is at rest)
    pivots, lower = factorise(grid, 0.0)
    elastic_force = grid.stiffness_times(w0)
    accel_rhs = -elastic_force.copy()
    accel_rhs[node] += external[0] if n_steps else 0.0
    accel_rhs[grid.constrained] = 0.0
    accel = tridiagonal_solve(pivots, lower, accel_rhs)
    v0 = -0.5 * dt * accel
    # initial strain energy, corrected by the start-up half step of the discrete identity
    initial_energy = 0.5 * float(w0 @ elastic_force) - 0.5 * dt * float(elastic_force @ v0)
    drive = Drive(False, 1.0, 0.0, 0.0, node, external)
    result, state = run_loop(beam, grid, LinearContact.kernel, np.ones(1), drive,
                             Stepping(dt, n_steps, stride), w0, v0, gauge_left, gauge_weight)
    n_rec = result.records
    rec = state["records"]
    history = pd.DataFrame({
        "time_s": rec.time[:n_rec], "load_N": rec.force[:n_rec],
        "deflection_at_load_m": rec.wk[:n_rec], "velocity_at_load_m_s": rec.vk[:n_rec],
        **gauge_columns(rec, beam.height, n_rec),
    })
    energies = beam_energies(grid, result, state["v"])
    # the kinetic energy of the start-up half step ½ v^{-1/2} M v^{-1/2} is part of the input
    start_kinetic = kinetic_energy(grid, v0)
    load_work = float(result.contact_work_beam)  # work of the applied load
    damping_work = float(result.damping_work)
    total = energies["beam_kinetic_energy"] + energies["beam_elastic_energy"] \
        + energies["beam_plastic_work"] + damping_work
    reference = load_work + initial_energy + start_kinetic
    scale = max(abs(load_work) + initial_energy, 1e-300)
    energy = dict(load_work=load_work, initial_energy=initial_energy + start_kinetic, **energies,
                  damping_work=damping_work, energy_balance_error=(total - reference) / scale)
    residual = residual_state(beam, grid, result.curvature, state) if n_steps else None
    return FDResponse(history=history, final_deflection=state["w"].copy(), energy=energy,
                      time_step=dt, load_node_position=node * grid.dx, residual=residual)
