"""Exact propagation of a linear contact phase through the coupled modes (numba).

While a linear contact is closed, impactor, contact spring and the retained undamped
modes form one linear system whose force is a sum of coupled oscillators, propagated
exactly for any step; the step only samples F(t) to locate its peak and end, fine near
them and coarse where that provably changes nothing. Derivation and error bounds:
docs/physics.rst, "Exact linear contact phase".
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from ..._checks import require_positive
from ...targets.base import ModalBasis
from .coupled_closed_form import (
    _advance,
    _clear_gap,
    _content_step,
    _first_positive,
    _partial_force,
)
from .kernel_types import kernel_array
from .coupled_stepping import _coarse_plan, _coarse_steps, _fine_steps

__all__ = [ "CONTACT_RESOLUTION", "CoupledModes",
           "contact_phase", "coupled_modes"]

#: ε of the contact-phase step rule: coupled modes whose force amplitudes sum to at most
#: ε/2 of the force content are not sampled (module docstring) [-].
CONTACT_RESOLUTION = 1e-5


@dataclass(frozen=True)
class CoupledModes:
    """The coupled modes of impactor + linear contact + retained modes: ``frequencies`` Ω_k
    [rad/s] ascending, ``force_row`` c_k (``F = Σ c_k η_k``), ``from_coupled`` (x =
    from_coupled @ η, x = (w_i, q_1 … q_n)) and ``to_coupled`` (η = to_coupled @ x).
    """

    frequencies: np.ndarray
    force_row: np.ndarray
    from_coupled: np.ndarray
    to_coupled: np.ndarray


def coupled_modes(basis: ModalBasis, contact_stiffness: float, impactor_mass: float) -> CoupledModes | None:
    """The :class:`CoupledModes` of a linear contact phase on ``basis`` (φ_j [1/sqrt(kg)], r
    [m/N]) with ``contact_stiffness`` K [N/m] and ``impactor_mass`` m_i [kg]; ``None`` for
    damped or rigid-body modes (then the sampled scheme runs).
    """
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("impactor_mass", impactor_mass, "kg")
    applies, frequencies, force_row, from_coupled, to_coupled = _coupled_arrays(
        kernel_array(basis.frequencies), kernel_array(basis.participation), kernel_array(basis.damping_ratios),
        float(basis.residual_compliance), float(contact_stiffness), float(impactor_mass))
    return CoupledModes(frequencies, force_row, from_coupled, to_coupled) if applies else None


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _coupled_arrays(frequencies, participation, damping_ratios, residual, contact_stiffness, impactor_mass):
    """The arrays of :class:`CoupledModes`, compiled: ``(applies, Ω, c, from_coupled,
    to_coupled)``; ``applies`` False (empty arrays) for damped or rigid-body modes or a
    coupled stiffness not positive definite. Same bits as the NumPy arithmetic.
    """
    size = frequencies.shape[0]
    for j in range(size):
        if damping_ratios[j] > 0.0 or frequencies[j] <= 0.0:
            return False, np.empty(0), np.empty(0), np.empty((0, 0)), np.empty((0, 0))
    effective = contact_stiffness / (1.0 + contact_stiffness * residual)
    # g = (1, −φ), M^{-1/2} = diag(s0, 1 … 1) with s0 = 1/sqrt(m_i); a product or quotient by
    # the ones is exact, so only the impactor's entries are scaled
    gvec = np.empty(size + 1)
    gvec[0] = 1.0
    for j in range(size):
        gvec[j + 1] = -participation[j]
    s0 = 1.0 / np.sqrt(impactor_mass)
    scaled = gvec.copy()  # M^{-1/2} g
    scaled[0] = s0 * 1.0
    stiffness = np.empty((size + 1, size + 1))
    for i in range(size + 1):
        for j in range(size + 1):
            stiffness[i, j] = (scaled[i] * scaled[j]) * effective
    for j in range(size):
        stiffness[j + 1, j + 1] += frequencies[j] ** 2
    eigenvalues, vectors = np.linalg.eigh(stiffness)
    if not eigenvalues[0] > 0.0:
        return False, np.empty(0), np.empty(0), np.empty((0, 0)), np.empty((0, 0))
    from_coupled = np.empty((size + 1, size + 1))  # element loops: copies, never views of ``vectors``
    to_coupled = np.empty((size + 1, size + 1))
    for i in range(size + 1):
        for k in range(size + 1):
            from_coupled[i, k] = vectors[i, k]
            to_coupled[k, i] = vectors[i, k]
    for k in range(size + 1):
        from_coupled[0, k] *= s0
        to_coupled[k, 0] /= s0
    force_row = effective * np.dot(gvec, from_coupled)
    return True, np.sqrt(eigenvalues), force_row, from_coupled, to_coupled


@numba.njit(cache=True)
def _least_advance(t, length):
    """The least shift s = 10⁻¹⁴ length · 2^k [s] (k ≥ 0) with t + s > t (t [s])."""
    s = 1e-14 * length
    while t + s <= t:
        s *= 2.0
    return s


@numba.njit(cache=True, no_cfunc_wrapper=True)
def contact_phase(coupled, modes, limits, start, q, v, record, history, rec, two_rate=True):
    """One contact, from touchdown (α = 0) to separation or the run's limits.

    Parameters
    ----------
    coupled, modes : KernelCoupled, KernelModes
        The coupled modes and the retained modes.
    limits : tuple
        (max_time [s], max_steps).
    start : tuple
        (t [s], w_i [m], v_i [m/s], peak [N], peak time [s], steps) at touchdown.
    q, v : ndarray
        Modal state at touchdown, overwritten with the state at the end.
    record, history, rec
        Whether to record, the history rows and the next row.
    two_rate : bool
        Take coarse steps where proven to change nothing.

    Returns
    -------
    tuple
        (t, wi, vi, force, peak, peak_time, steps, separated, history, rec) at the end
        (``force`` 0 after a separation; a graze returns ``steps`` unchanged).
    """
    frequencies, force_row, from_coupled, to_coupled = (coupled.frequencies, coupled.force_row,
                                                        coupled.from_coupled, coupled.to_coupled)
    omega, phi, residual = modes.frequencies, modes.participation, modes.residual
    t, wi, vi, peak, peak_time, steps = start
    n = frequencies.shape[0]
    eta = np.empty(n)
    rate = np.empty(n)
    for k in range(n):
        eta[k] = to_coupled[k, 0] * wi
        rate[k] = to_coupled[k, 0] * vi
        for j in range(1, n):
            eta[k] += to_coupled[k, j] * q[j - 1]
            rate[k] += to_coupled[k, j] * v[j - 1]
    h = coupled.step_scale * _content_step(frequencies, force_row, eta, rate, CONTACT_RESOLUTION)
    if h == 0.0 or _first_positive(frequencies, force_row, eta, rate, h) == 0.0:
        # grazing: no force anywhere in the first step (a touchdown at zero closing speed
        # whose force grows at second order — a sphere resting on a structure that
        # accelerates into it — is a contact: its force is positive just after touchdown);
        # leave with the gap strictly open and a later time, or flight would find this
        # touchdown again and no time would pass (tests/solvers/test_graze_spin.py)
        if h == 0.0:
            h = 1e-9 / frequencies[n - 1]
        s, wi, vi = _clear_gap(from_coupled, frequencies, eta, rate, phi, _least_advance(t, h), h, np.empty(n),
                               np.empty(n), q, v)
        return t + s, wi, vi, 0.0, peak, peak_time, steps, True, history, rec
    resolved = 0  # coupled modes sampled at least 2π times per period (ascending Ω)
    while resolved < n and frequencies[resolved] * h <= 1.0:
        resolved += 1
    phase_modes = (frequencies, force_row, from_coupled)
    rows = (coupled.row_spacing, omega, phi, residual)
    fine = (h, np.cos(frequencies * h), np.sin(frequencies * h), resolved)
    coarse = _coarse_plan(frequencies, force_row, eta, rate, h) if two_rate else \
        (0, 0.0, np.empty(0), np.empty(0), 0, 0.0)
    state = (eta, rate, np.empty(n), np.empty(n))
    run = (t, 0.0, -1.0, peak, peak_time, steps)  # no force, and no sample before touchdown
    while True:
        state, run, separated, stopped, wi, vi, history, rec = _fine_steps(
            phase_modes, rows, fine, coarse, limits, state, run, record, history, rec, q, v)
        t, force, f_prev, peak, peak_time, steps = run
        if not stopped:
            return t, wi, vi, force, peak, peak_time, steps, separated, history, rec
        eta, rate, (t, force, peak, peak_time, steps), done, wi, vi, history, rec = _coarse_steps(
            phase_modes, rows, coarse, limits, (state[0], state[1]), (t, force, peak, peak_time, steps),
            record, history, rec, q, v)
        if done:
            return t, wi, vi, force, peak, peak_time, steps, False, history, rec
        # a fine window from a coarse sample: the sample one fine step before, exactly
        eta_prev = np.empty(n)
        rate_prev = np.empty(n)
        _advance(frequencies, eta, rate, -h, eta_prev, rate_prev)
        f_prev = _partial_force(force_row, eta_prev, n)
        state = (eta, rate, eta_prev, rate_prev)
        run = (t, force, f_prev if f_prev > 0.0 else -1.0, peak, peak_time, steps)
