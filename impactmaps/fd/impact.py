"""Impact of a rigid sphere on the finite-difference Rayleigh beam: :func:`simulate_fd`.

Gravity acts on the sphere only (docs/fd_beam.rst).
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import pandas as pd

from .._checks import require_positive
from ..contact.base import ContactLaw
from ..contact.contact_scale import reference_contact_stiffness
from ..result import ImpactResult
from ..solvers.run_budget import refuse_or_announce
from ..targets.beams.beam import Beam
from .._checks import ModelValidityWarning
from ._loop import Drive, Stepping, run_loop
from .beam import FDBeam, FDSettings
from .energy import impact_ledger
from .grid import beam_grid, gauge_columns, gauge_weights, node_for
from .residual import residual_state
from .timestep import choose_time_step, contact_rate, single_case_parameters
from .wide_section import CALIBRATED_RATIO

#: Width/height above which a yielding *uniaxial* layered section (``width_constraint=False``)
#: under-predicts the hinge (the 3D hinge is held across the width): measured against a 3D
#: elastic–perfectly-plastic beam in validation/fe/level5_* (docs/validation.rst, FE level 5).
WIDE_SECTION_RATIO = 1.0

__all__ = ["FDDetails", "STANDARD_GRAVITY", "estimate_fd", "simulate_fd"]

#: Standard acceleration of gravity [m/s²] (3rd CGPM, 1901).
STANDARD_GRAVITY = 9.80665

@dataclass(frozen=True)
class FDDetails:
    """What only the finite-difference beam knows of an impact (``ImpactResult.details``).

    Attributes
    ----------
    permanent_beam_deflection : float
        Permanent deflection at the impact node [m] (elastic unloading of the final state).
    final_mean_deflection : float
        Mean deflection at the impact node over the last 20 % of the record [m].
    energy : dict
        The ledger [J]: ``impact_kinetic_energy``, ``gravity_work``,
        ``impactor_kinetic_energy``, ``rebound_kinetic_energy``, ``beam_kinetic_energy``,
        ``beam_elastic_energy``, ``beam_plastic_work``, ``contact_dissipation``,
        ``contact_stored_energy``, ``damping_work``, ``contact_work_discrete`` and
        ``energy_balance_error`` (relative to the impact energy) [-].
    residual : pandas.DataFrame
        Per node: ``x_m, final_deflection_m, permanent_deflection_m,
        residual_curvature_1_m, max_plastic_strain, plastic_work_J_m``.
    impact_position, impact_node_position : float
        Requested impact point and the loaded node [m].
    stability_limit : float
        Stability limit of the explicit scheme [s].
    gauge_positions : tuple of float
        Gauge positions [m] (columns ``gauge{g}_deflection_m``, ``gauge{g}_strain``).
    """

    permanent_beam_deflection: float
    final_mean_deflection: float
    energy: dict
    residual: pd.DataFrame
    impact_position: float
    impact_node_position: float
    stability_limit: float
    gauge_positions: tuple

    @property
    def plastic_zone(self):
        """(x_min, x_max) [m] of the nodes that have yielded, or ``None``."""
        plastic = self.residual["max_plastic_strain"].to_numpy() > 0
        if not plastic.any():
            return None
        x = self.residual["x_m"].to_numpy()[plastic]
        return float(x.min()), float(x.max())

    def summary(self) -> dict:
        """The finite-difference scalars with unit-suffixed keys (the whole ledger)."""
        out = {"permanent_beam_deflection_m": float(self.permanent_beam_deflection)}
        out.update({f"{k}_J" if k != "energy_balance_error" else k: float(v)
                    for k, v in self.energy.items()})
        return out


def simulate_fd(beam, law: ContactLaw, impactor_mass, velocity, impact_position=None, *,
                settings: FDSettings | None = None, material=None, **options) -> ImpactResult:
    """Impact of a rigid sphere on a finite-difference Rayleigh beam.

    Parameters
    ----------
    beam : FDBeam or impactmaps.targets.beams.beam.Beam
        An :class:`FDBeam`, or a rectangular isotropic ``Beam`` with its ``material``.
    law : ContactLaw
        Contact law of a single case (e.g. ``law_for_sphere("stronge", sphere, beam)``).
    impactor_mass : float
        Sphere mass m [kg] (> 0).
    velocity : float
        Impact velocity V0 [m/s] (> 0), in the +w direction.
    impact_position : float, optional
        x0 [m] (default mid-span or the Beam's); loaded at the nearest node, which must
        not be supported.
    settings : FDSettings, optional
        All numerical options in one object (then leave out the keywords below).
    material : material-like, optional
        The material of a toolkit ``Beam`` (required with one, refused with an FDBeam).
    **options
        ``duration`` [s] (required here or in ``settings``), ``time_step`` [s],
        ``safety_factor``, ``gauge_positions`` [m], ``gravity``, ``history_stride``: as
        in :class:`FDSettings`; another keyword is a ``TypeError``.

    Returns
    -------
    ImpactResult
        ``method = "finite-difference"``; ``details`` is an :class:`FDDetails`.

    Raises
    ------
    ValueError
        For an invalid input, named, or a ``time_step`` above the stability limit.
    """
    plan = _prepare(beam, law, impactor_mass, velocity, impact_position, settings, material, options)
    budget, what = _budget(plan)
    refuse_or_announce(budget, what, stacklevel=3)
    beam, settings, params, grid, x0, node = plan.beam, plan.settings, plan.params, plan.grid, plan.x0, plan.node
    positions, gauge_left, gauge_weight = plan.positions, plan.gauge_left, plan.gauge_weight
    contact_stiffness, dt, limit = plan.contact_stiffness, plan.dt, plan.limit
    impactor_mass, velocity = plan.impactor_mass, plan.velocity
    n_steps = int(math.ceil(plan.steps))
    g = STANDARD_GRAVITY if settings.gravity else 0.0

    n = grid.n_nodes
    drive = Drive(True, impactor_mass, velocity, g, node, np.zeros(0))
    result, state = run_loop(beam, grid, law.kernel, params, drive,
                             Stepping(dt, n_steps, settings.history_stride), np.zeros(n),
                             np.zeros(n), gauge_left, gauge_weight)
    n_rec = result.records
    rec = state["records"]
    time, wk = rec.time[:n_rec], rec.wk[:n_rec]
    history = _history_frame(rec, n_rec, beam.height)
    separation_velocity = _separation_velocity(result, state["intervals"], n_steps * dt)
    energy, contact = impact_ledger(law, grid, result, state["v"], impactor_mass, velocity,
                                    separation_velocity)
    residual = residual_state(beam, grid, result.curvature, state)
    _warn_if_wide_section_yields(beam, residual)
    return ImpactResult(
        history=history,
        peak_force=float(result.peak_force),
        peak_time=float(result.peak_time),
        contact_intervals=np.asarray(state["intervals"], float).reshape(-1, 2),
        max_indentation=float(result.alpha_max),
        permanent_indentation=contact["permanent_indentation"],
        rebound_velocity=float(-separation_velocity),
        energy_transferred=energy["beam_kinetic_energy"] + energy["beam_elastic_energy"],
        contact_dissipation=energy["contact_dissipation"],
        damping_work=energy["damping_work"],
        energy_balance_error=energy["energy_balance_error"],
        impactor_mass=impactor_mass,
        velocity=velocity,
        contact_frequency=float(np.sqrt(reference_contact_stiffness(law, impactor_mass, velocity)
                                        / impactor_mass)),
        end_time=float(n_steps * dt),
        time_limit_reached=bool(result.in_contact),
        time_step=dt,
        method="finite-difference",
        settings=dict(beam=beam, law=law.name, duration=float(settings.duration), gravity=g,
                      history_stride=settings.history_stride,
                      safety_factor=float(settings.safety_factor), n_steps=n_steps,
                      contact_stiffness_bound=contact_stiffness),
        details=FDDetails(
            permanent_beam_deflection=float(residual["permanent_deflection_m"].iloc[node]),
            final_mean_deflection=float(np.mean(wk[time >= 0.8 * time[-1]])), energy=energy, residual=residual,
            impact_position=x0, impact_node_position=node * grid.dx, stability_limit=limit,
            gauge_positions=positions),
    )


def _check_inputs(law, impactor_mass, velocity, settings) -> None:
    """``ValueError`` naming the input of :func:`simulate_fd` that is not valid."""
    if not isinstance(law, ContactLaw):
        raise ValueError(f"law = {law!r} is not a ContactLaw")
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    if settings.duration is None:
        raise ValueError("duration is required (simulated time [s], valid range (0, inf))")


def _history_frame(rec, n_rec: int, height: float) -> pd.DataFrame:
    """The recorded rows of a run as the history DataFrame (SI columns, gauges last)."""
    return pd.DataFrame({
        "time_s": rec.time[:n_rec],
        "force_N": rec.force[:n_rec],
        "indentation_m": rec.alpha[:n_rec],
        "impactor_velocity_m_s": rec.vs[:n_rec],
        "impactor_displacement_m": rec.u[:n_rec],
        "target_displacement_m": rec.wk[:n_rec],
        "target_velocity_m_s": rec.vk[:n_rec],
        **gauge_columns(rec, height, n_rec),
    })


#: The keywords :func:`simulate_fd` takes for the run options (fields of :class:`FDSettings`).
_RUN_OPTIONS = ("duration", "time_step", "safety_factor", "gauge_positions", "gravity", "history_stride")


def _run_settings(settings, **keywords) -> FDSettings:
    """The run's FDSettings: ``settings`` as given, or built from the keywords."""
    unknown = sorted(set(keywords) - set(_RUN_OPTIONS))
    if unknown:
        raise TypeError(f"simulate_fd() got an unexpected keyword argument {unknown[0]!r}")
    given = {name: value for name, value in keywords.items() if value is not None}
    if settings is None:
        return FDSettings(**given)
    if not isinstance(settings, FDSettings):
        raise ValueError(f"settings = {settings!r} is not an FDSettings")
    if given:
        raise ValueError(f"{', '.join(sorted(given))} given both as keyword(s) and through "
                         "settings: give the run options in one place")
    return settings


def _fd_beam(beam, material, settings, impact_position):
    """(FDBeam, impact position) of the run from an FDBeam or a toolkit Beam."""
    if isinstance(beam, FDBeam):
        if material is not None:
            raise ValueError(f"material = {material!r} is only used with a toolkit Beam: an "
                             "FDBeam carries its own material")
        options = settings.beam_options()
        return (dataclasses.replace(beam, **options) if options else beam), impact_position

    if isinstance(beam, Beam):
        if material is None:
            raise ValueError("material is required with a toolkit Beam (youngs_modulus [Pa], "
                             "density [kg/m^3], yield_strength [Pa], poisson_ratio [-])")
        position = beam.impact_position if impact_position is None else impact_position
        return FDBeam.from_beam(beam, material, settings), position
    raise ValueError(f"beam = {beam!r} is not an FDBeam or an impactmaps.targets.beams.beam.Beam")


#: Node-layer steps per second of the compiled loop, measured on the 2-core reference
#: machine (benchmarks/bench_fd.py: 15 943 steps × 201 nodes × 20 layers in ≈ 0.09 s).
NODE_LAYER_STEPS_PER_SECOND = 7e8


def _warn_if_wide_section_yields(beam, residual) -> None:
    """A ``ModelValidityWarning`` when the section yielded outside the b/h range its model was checked in."""
    ratio = float(beam.width) / float(beam.height)
    if float(np.max(residual["max_plastic_strain"])) <= 0.0:
        return
    if not beam.width_constraint and ratio > WIDE_SECTION_RATIO:
        warnings.warn(
            f"beam section: it yielded with width/height = {ratio:.3g} > {WIDE_SECTION_RATIO:g} and "
            "width_constraint=False: the uniaxial layered section's plastic hinge is weaker than a wide "
            "beam's (held across its width); against 3D finite elements at width/height 2.2 the peak "
            "deflection came out 6.6 % and the permanent deflection 23 % too large (docs/validation.rst, "
            "FE level 5)", ModelValidityWarning, stacklevel=3)
    elif beam.width_constraint and ratio > CALIBRATED_RATIO:
        warnings.warn(
            f"beam section: it yielded with width/height = {ratio:.3g} > {CALIBRATED_RATIO:g}, beyond the "
            "3D calibration of the wide-section model (impactmaps.fd.wide_section): the hinge capacity "
            "there is an extrapolation (docs/validation.rst, FE level 5)", ModelValidityWarning,
            stacklevel=3)


class _Plan(NamedTuple):
    """What a run is made of, before anything is integrated (:func:`_prepare`)."""

    beam: FDBeam
    settings: FDSettings
    params: np.ndarray
    grid: object
    x0: float
    node: int
    positions: np.ndarray
    gauge_left: np.ndarray
    gauge_weight: np.ndarray
    contact_stiffness: float
    dt: float
    limit: float
    steps: float
    impactor_mass: float
    velocity: float


def _prepare(beam, law, impactor_mass, velocity, impact_position, settings, material, options) -> _Plan:
    """Check the inputs of :func:`simulate_fd` and plan its run: grid, impact node, gauges, step,
    number of steps (a float: a huge duration is refused, not overflowed). Arithmetic only."""
    settings = _run_settings(settings, **options)
    beam, impact_position = _fd_beam(beam, material, settings, impact_position)
    _check_inputs(law, impactor_mass, velocity, settings)
    params = single_case_parameters(law, "simulate_fd")
    impactor_mass, velocity = float(impactor_mass), float(velocity)
    grid = beam_grid(beam)
    x0, node = node_for(beam, grid, impact_position, "impact_position")
    positions, gauge_left, gauge_weight = gauge_weights(beam, settings.gauge_positions)
    contact_stiffness, rate = contact_rate(grid, node, law, params, impactor_mass, velocity)
    dt, limit = choose_time_step(grid, settings.time_step, settings.safety_factor, rate)
    return _Plan(beam, settings, params, grid, x0, node, positions, gauge_left, gauge_weight, contact_stiffness,
                 dt, limit, float(settings.duration) / dt, impactor_mass, velocity)


def _budget(plan: _Plan):
    """The run budget of a planned run and the run in words (:mod:`impactmaps.solvers.run_budget`,
    shared with the modal solver: refused above 1 GiB of history, announced above a minute)."""
    from ..solvers.run_budget import MEMORY_LIMIT_BYTES, RunBudget

    settings, n_steps = plan.settings, plan.steps
    n_nodes, n_gauges = plan.grid.n_nodes, len(plan.positions)
    records = n_steps / settings.history_stride + 1.0  # floats throughout: inf refuses, never overflows
    history_bytes = records * (7 + 2 * n_gauges) * 8 * 2
    needed = history_bytes * settings.history_stride / MEMORY_LIMIT_BYTES
    budget = RunBudget(
        min(history_bytes, 1e300), n_steps * n_nodes * 2 * plan.beam.n_half_layers / NODE_LAYER_STEPS_PER_SECOND,
        (f"the history would; use history_stride ≥ {math.ceil(needed)} or a shorter duration" if needed < 1e15
         else "the history would; use a shorter duration"),
        "the step is bounded by the grid's stability limit, ∝ Δx²; fewer elements or a shorter duration are faster")
    what = (f"duration = {settings.duration:g} s is {_count(n_steps)} steps of {plan.dt:.3g} s: the "
            f"finite-difference run of {n_nodes} nodes")
    return budget, what


def estimate_fd(beam, law: ContactLaw, impactor_mass, velocity, impact_position=None, *,
                settings: FDSettings | None = None, material=None, **options) -> dict:
    """What :func:`simulate_fd` would cost, from arithmetic alone (nothing is integrated).

    Parameters are those of :func:`simulate_fd`.

    Returns
    -------
    dict
        ``time_step_s``, ``steps``, ``nodes``, ``history_rows``, ``memory_bytes`` (the
        history: refused above 1 GiB) and ``seconds`` (on the 2-core reference machine:
        announced above a minute); ``refused`` (the refusal's text, or ``None``).
    """
    plan = _prepare(beam, law, impactor_mass, velocity, impact_position, settings, material, options)
    budget, what = _budget(plan)
    from ..solvers.run_budget import MEMORY_LIMIT_BYTES

    refused = None
    if budget.memory_bytes > MEMORY_LIMIT_BYTES:
        refused = (f"{what} may take {budget.memory_bytes / 2**30:.3g} GiB (limit "
                   f"{MEMORY_LIMIT_BYTES / 2**30:g} GiB): {budget.advice}")
    return {"time_step_s": plan.dt, "steps": float(math.ceil(plan.steps)) if plan.steps < 1e15 else plan.steps,
            "nodes": int(plan.grid.n_nodes), "history_rows": plan.steps / plan.settings.history_stride + 1.0,
            "memory_bytes": float(budget.memory_bytes), "seconds": float(budget.seconds), "refused": refused}


def _count(steps: float) -> str:
    """A step count as text: the integer, or three digits when it is astronomical."""
    return f"{math.ceil(steps)}" if steps < 1e15 else f"{steps:.3g}"


def _separation_velocity(result, intervals, end_time) -> float:
    """Sphere velocity at the last separation [m/s]; nan (with a warning) if none."""
    if result.in_contact or intervals.shape[0] == 0:
        if intervals.shape[0] == 0:
            warnings.warn("the sphere never touched the beam", stacklevel=3)
        else:
            warnings.warn(
                f"the record ends in contact at t = {end_time:g} s: rebound velocity, "
                "restitution and energy loss are undefined (nan); increase duration",
                stacklevel=3)
        return np.nan
    return float(result.separation_velocity)
