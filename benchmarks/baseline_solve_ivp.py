"""Baseline: the modal impact equations integrated by scipy ``solve_ivp`` (DOP853).

This is the "straightforward" way to solve the problem of docs/physics_contract.md §3.4, used (a) as
the speed baseline of :mod:`benchmarks.bench_modal` and (b) at tight tolerances as the
independent reference of ``tests/solvers/test_integrator.py``. It shares nothing with the
impactmaps integrator except the modal basis, which is built exactly as
:func:`impactmaps.solvers.modal.simulate` builds it (same cut-off, same dropped
insignificant modes, same residual compliance of the dropped modes).

Equations (linear contact of stiffness K, residual compliance r in series)::

    q̈_j + 2ζ_jω_j q̇_j + ω_j² q_j = φ_j F,      m_i ẅ_i = −F,
    α = w_i − Σ φ_j q_j − r F,   F = K max(α, 0)
    ⇒ F = K max(w_i − Σ φ_j q_j, 0) / (1 + K r).

They are integrated in the normalised variables of the spec (τ = ωt, ω = sqrt(K/m_i),
displacements over α* = V0/ω, F̄ = F/(m_i V0 ω)), with ``p_j = φ_j q_j/α*`` the
contribution of mode j to the target deflection at the impact point::

    w̄'' = −F̄,   p_j'' + 2ζ_jΩ_j p_j' + Ω_j² p_j = m_i φ_j² F̄,   Ω_j = ω_j/ω,
    F̄ = max(w̄ − Σ p_j, 0) / (1 + K r),

so every state is O(1) and the absolute tolerance is an absolute tolerance on F̄ (the
same equations, only scaled; in SI units an absolute tolerance of 1e-10 m would mean
very different things for a 2 g and a 160 kg impactor).

Contact and separation are handled by events: a contact phase (F̄ linear in the state,
smooth right-hand side) ends at the root of ``w̄ − Σp = 0`` crossed downwards, a free
phase ends at its upward crossing. Local force maxima are located by a non-terminal
event on ``w̄' − Σp' = 0`` (crossed downwards) inside contact phases, i.e. by a root
search on the dense output, so F̄max carries no sampling error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from impactmaps.solvers.modal import ModalSettings, basis_for
from impactmaps.targets.base import ModalBasis

__all__ = ["BaselineResult", "impact_basis", "solve_ivp_fmax", "baseline_like"]


@dataclass(frozen=True)
class BaselineResult:
    """Outcome of one ``solve_ivp`` impact run (normalised quantities).

    Attributes
    ----------
    fmax_normalised : float
        F̄max = F_max/(m_i V0 ω) over all contacts [-].
    peak_time_normalised : float
        ω · time of the maximum [-].
    impacts : int
        Number of separate contacts [-].
    end_time_normalised : float
        ω · end time of the run [-].
    function_evaluations : int
        Right-hand-side evaluations over all phases [-].
    n_modes : int
        Modes integrated [-].
    """

    fmax_normalised: float
    peak_time_normalised: float
    impacts: int
    end_time_normalised: float
    function_evaluations: int
    n_modes: int


def impact_basis(target, contact_stiffness: float, impactor_mass: float,
                 settings: ModalSettings | None = None) -> ModalBasis:
    """The modal basis :func:`impactmaps.solvers.modal.simulate` integrates.

    Parameters
    ----------
    target : Target or ModalBasis
        As passed to ``simulate``.
    contact_stiffness : float
        Linear contact stiffness K [N/m].
    impactor_mass : float
        m_i [kg].
    settings : ModalSettings, optional
        The settings of the impactmaps run (cut-off, ``min_modes``, residual flag).

    Returns
    -------
    ModalBasis
        Frequencies [rad/s], participations [kg^-1/2], residual compliance [m/N].
    """
    settings = settings or ModalSettings()
    omega = math.sqrt(contact_stiffness / impactor_mass)
    return basis_for(target, omega, settings)


def solve_ivp_fmax(
    basis: ModalBasis,
    contact_stiffness: float,
    impactor_mass: float,
    end_time: float,
    *,
    rtol: float = 1e-8,
    atol: float = 1e-10,
    method: str = "DOP853",
    max_phases: int = 10_000,
) -> BaselineResult:
    """Integrate the linear-contact modal impact with ``scipy.integrate.solve_ivp``.

    Parameters
    ----------
    basis : ModalBasis
        Modes at the impact point, with the residual compliance of the dropped modes
        (placed in series with the contact). Use :func:`impact_basis`.
    contact_stiffness : float
        K [N/m].
    impactor_mass : float
        m_i [kg].
    end_time : float
        Stop time [s] (take the ``end_time`` of the impactmaps run to compare).
    rtol, atol : float
        ``solve_ivp`` tolerances; ``atol`` is absolute on the normalised states (F̄).
    method : str
        ``solve_ivp`` method (default DOP853).
    max_phases : int
        Safety limit on the number of contact/free phases.

    Returns
    -------
    BaselineResult
        The velocity drops out of the normalised result (linear problem).
    """
    omega_c = math.sqrt(contact_stiffness / impactor_mass)
    big_omega = basis.frequencies / omega_c
    omega2 = big_omega**2
    damping = 2.0 * basis.damping_ratios * big_omega
    coupling = impactor_mass * basis.participation**2
    series = 1.0 / (1.0 + contact_stiffness * basis.residual_compliance)
    n = basis.size
    tau_end = end_time * omega_c

    def rhs_contact(_tau, y):
        force = (y[0] - y[2:2 + n].sum()) * series
        out = np.empty_like(y)
        out[0] = y[1]
        out[1] = -force
        out[2:2 + n] = y[2 + n:]
        out[2 + n:] = coupling * force - omega2 * y[2:2 + n] - damping * y[2 + n:]
        return out

    def rhs_free(_tau, y):
        out = np.empty_like(y)
        out[0] = y[1]
        out[1] = 0.0
        out[2:2 + n] = y[2 + n:]
        out[2 + n:] = -omega2 * y[2:2 + n] - damping * y[2 + n:]
        return out

    def gap(_tau, y):
        return y[0] - y[2:2 + n].sum()

    def gap_rate(_tau, y):
        return y[1] - y[2 + n:].sum()

    def separation(tau, y):
        return gap(tau, y)

    def touchdown(tau, y):
        return gap(tau, y)

    def peak(tau, y):
        return gap_rate(tau, y)

    separation.terminal, separation.direction = True, -1.0
    touchdown.terminal, touchdown.direction = True, 1.0
    peak.terminal, peak.direction = False, -1.0

    y = np.zeros(2 + 2 * n)
    y[1] = 1.0  # w̄'(0) = V0/(ω α*) = 1; first touch at τ = 0
    tau = 0.0
    in_contact = True
    impacts = 1
    fmax = 0.0
    peak_time = 0.0
    evaluations = 0
    for _ in range(max_phases):
        if tau >= tau_end:
            break
        if in_contact:
            sol = solve_ivp(rhs_contact, (tau, tau_end), y, method=method, rtol=rtol, atol=atol,
                            events=(separation, peak))
            for t_peak, y_peak in zip(sol.t_events[1], sol.y_events[1]):
                force = gap(t_peak, y_peak) * series
                if force > fmax:
                    fmax, peak_time = force, t_peak
            # the force at step ends too (a maximum at the phase end has no event)
            forces = (sol.y[0] - sol.y[2:2 + n].sum(axis=0)) * series
            k = int(np.argmax(forces))
            if forces[k] > fmax:
                fmax, peak_time = float(forces[k]), float(sol.t[k])
        else:
            sol = solve_ivp(rhs_free, (tau, tau_end), y, method=method, rtol=rtol, atol=atol,
                            events=(touchdown,))
        evaluations += sol.nfev
        if not sol.success:
            raise RuntimeError(f"solve_ivp failed: {sol.message}")
        if sol.status == 1 and sol.t_events[0].size:
            tau = float(sol.t_events[0][0])
            y = np.array(sol.y_events[0][0])
            in_contact = not in_contact
            if in_contact:
                impacts += 1
        else:
            tau = float(sol.t[-1])
            y = sol.y[:, -1]
    else:
        raise RuntimeError(f"more than max_phases = {max_phases} contact/free phases")
    return BaselineResult(
        fmax_normalised=float(fmax),
        peak_time_normalised=float(peak_time),
        impacts=impacts,
        end_time_normalised=float(tau_end),
        function_evaluations=int(evaluations),
        n_modes=n,
    )


def baseline_like(result, target, settings: ModalSettings | None = None, *,
                  rtol: float = 1e-8, atol: float = 1e-10) -> BaselineResult:
    """Re-run an impactmaps linear-contact run with ``solve_ivp`` (same modes, same end).

    Parameters
    ----------
    result : ImpactResult
        Output of :func:`impactmaps.solvers.modal.simulate` with a ``LinearContact``.
    target : Target or ModalBasis
        The target passed to ``simulate``.
    settings : ModalSettings, optional
        The settings passed to ``simulate``.
    rtol, atol : float
        ``solve_ivp`` tolerances.

    Returns
    -------
    BaselineResult
    """
    stiffness = result.impactor_mass * result.contact_frequency**2
    basis = impact_basis(target, stiffness, result.impactor_mass, settings)
    if basis.size != result.n_modes:
        raise RuntimeError(
            f"basis rebuilt with {basis.size} modes but the impactmaps run used {result.n_modes}"
        )
    return solve_ivp_fmax(basis, stiffness, result.impactor_mass, result.end_time, rtol=rtol, atol=atol)
