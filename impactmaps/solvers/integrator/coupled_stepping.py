"""Two-rate stepping of a linear contact phase (numba).

:func:`_fine_steps` is the single-rate loop at the fine step h; :func:`_coarse_steps`
takes coarse steps H = N h where a bound proves they change nothing; :func:`_coarse_plan`
sets H and the bound (docs/physics.rst, "Exact linear contact phase").
"""

from __future__ import annotations

import numba
import numpy as np

from .coupled_closed_form import (
    _amplitudes,
    _clear_gap,
    _content_step,
    _first_positive,
    _force,
    _force_rate,
    _partial_force,
    _record_inside,
    _root,
    _step,
    _to_physical,
)
from .history_rows import record_row

__all__ = ["COARSE_FACTOR", "COARSE_RESOLUTION"]

#: ε of the coarse step of a two-rate contact phase (module docstring): the coupled
#: modes whose amplitudes sum to at most ε/2 of the force content set no coarse step
#: (3e-3: fewest steps over the quasi-static map points of the beam and the plate
#: against 1e-3, 5e-3, 1e-2 and 3e-2) [-].
COARSE_RESOLUTION = 3e-3
#: Fewest fine steps in a coarse step: below, the contact phase keeps the fine step
#: (2: 12 % less CPU than 4 over the quasi-static map points of the beam and the plate) [-].
COARSE_FACTOR = 2
#: ``derivative`` of :func:`_root` as booleans, not literals (a literal True and False would
#: compile it twice).
_OF_FORCE = np.bool_(False)
_OF_RATE = np.bool_(True)


@numba.njit(cache=True, no_cfunc_wrapper=True)
def _coarse_plan(frequencies, force_row, eta, rate, h):
    """The coarse rate of a contact whose fine step is h [s]: ``(every, H, cos Ω_k H,
    sin Ω_k H, low, margin)`` with H = every·h [s], ``low`` the slowest coupled modes with
    Ω_k H ≤ 1 and ``margin`` [N] the bound on F about the F_low samples; ``every`` is 0
    (single rate) under :data:`COARSE_FACTOR`.
    """
    content = _content_step(frequencies, force_row, eta, rate, COARSE_RESOLUTION)
    every = int(content / h)
    if every < COARSE_FACTOR:
        return 0, 0.0, np.empty(0), np.empty(0), 0, 0.0
    length = every * h
    amplitude = _amplitudes(frequencies, force_row, eta, rate)
    low = 0
    curvature = 0.0
    high = 0.0
    for k in range(eta.shape[0]):
        if frequencies[k] * length <= 1.0:
            low = k + 1
            curvature += amplitude[k] * frequencies[k] ** 2
        else:
            high += amplitude[k]
    margin = high + length * length / 8.0 * curvature
    return every, length, np.cos(frequencies * length), np.sin(frequencies * length), low, margin


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _skippable(frequencies, force_row, eta, rate, coarse, peak):
    """Whether the coarse step from the state (η, η̇) may be taken without the fine
    step: no instant in it can have F ≤ 0, nor F above ``peak`` [N] (:func:`_coarse_plan`)."""
    _every, _length, cos_c, sin_c, low, margin = coarse
    before = _partial_force(force_row, eta, low)
    if before <= margin or before + margin > peak:  # most samples of a fine window
        return False
    after = 0.0
    for k in range(low):
        after += force_row[k] * (eta[k] * cos_c[k] + rate[k] / frequencies[k] * sin_c[k])
    return after > margin and after + margin <= peak


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _record_step(modes, rows, start, end, t, length, force, history, rec, q, v):
    """Record a step of ``length`` [s] from time t [s]: exact rows inside, and its end
    (state ``end``, force [N]); q and v serve as scratch."""
    _frequencies, _force_row, from_coupled = modes
    _row_spacing, omega, phi, residual = rows
    history, rec = _record_inside(modes, rows, start, t, length, q, v, history, rec)
    wi, vi = _to_physical(from_coupled, end[0], end[1], q, v)
    return record_row(history, rec, t + length, force, wi, vi, residual, omega, phi, q, v)


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _fine_steps(modes, rows, fine, coarse, limits, state, run, record, history, rec, q, v):
    """Steps of the fine step h: the single-rate loop of the contact phase.

    ``state`` = (η, η̇, η_prev, η̇_prev); ``run`` = (t, F(t), F one step before (< 0: none),
    peak, peak time, steps). With ``coarse[0]`` = 0 it runs to the separation or the limits;
    otherwise it also stops (``stopped``) at the first sample from which the coarse step is
    :func:`_skippable`. Returns (state, run, separated, stopped, wi, vi, history, rec).
    """
    frequencies, force_row, from_coupled = modes
    _row_spacing, omega, phi, residual = rows
    h, cos_h, sin_h, resolved = fine
    every = coarse[0]
    max_time, max_steps = limits
    eta, rate, eta_prev, rate_prev = state
    t, force, f_prev, peak, peak_time, steps = run
    n = frequencies.shape[0]
    eta_next = np.empty(n)
    rate_next = np.empty(n)
    separated = False
    stopped = False
    taken = 0
    wi = 0.0
    vi = 0.0
    while True:
        _step(frequencies, eta, rate, cos_h, sin_h, eta_next, rate_next)
        f_next = 0.0
        for k in range(n):
            f_next += force_row[k] * eta_next[k]
        if f_next <= 0.0:
            steps += 1
            # the bracket starts where F > 0: at the step's start, or inside the first step
            start = 0.0 if force > 0.0 else _first_positive(frequencies, force_row, eta, rate, h)
            s = _root(frequencies, force_row, eta, rate, start, h, _OF_FORCE, n)
            # (η, η̇) at the separation land in eta_next, rate_next
            s, _wi, _vi = _clear_gap(from_coupled, frequencies, eta, rate, phi, s, h, eta_next, rate_next, q, v)
            if record:
                history, rec = _record_inside(modes, rows, (eta, rate), t, s, q, v, history, rec)
            t += s
            force = 0.0
            separated = True
        else:
            if f_prev >= 0.0 and force >= f_prev and force >= f_next:
                # a sampled maximum: the peak is where the rate of the sampled coupled modes
                # vanishes over the two steps around it (the force there, ripple included)
                if (_force_rate(frequencies, force_row, eta_prev, rate_prev, 0.0, resolved) > 0.0
                        and _force_rate(frequencies, force_row, eta_prev, rate_prev, 2.0 * h, resolved) < 0.0):
                    s = _root(frequencies, force_row, eta_prev, rate_prev, 0.0, 2.0 * h, _OF_RATE, resolved)
                    value = _force(frequencies, force_row, eta_prev, rate_prev, s)
                    if value > peak:
                        peak = value
                        peak_time = t - h + s
            if every > 0 and taken > 0 and _skippable(frequencies, force_row, eta, rate, coarse, peak):
                stopped = True
                break
            steps += 1
            taken += 1
            f_prev = force
            for k in range(n):  # element loop: a slice assignment compiles for seconds
                eta_prev[k] = eta[k]
                rate_prev[k] = rate[k]
            if record:
                history, rec = _record_inside(modes, rows, (eta, rate), t, h, q, v, history, rec)
            t += h
            force = f_next
            if force > peak:
                peak = force
                peak_time = t
        eta, eta_next = eta_next, eta
        rate, rate_next = rate_next, rate
        if record or separated or t >= max_time or steps >= max_steps:
            wi, vi = _to_physical(from_coupled, eta, rate, q, v)
            if record:
                history, rec = record_row(history, rec, t, force, wi, vi, residual, omega, phi, q, v)
        if separated or t >= max_time or steps >= max_steps:
            break
    return ((eta, rate, eta_prev, rate_prev), (t, force, f_prev, peak, peak_time, steps), separated, stopped,
            wi, vi, history, rec)


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _settle(modes, rows, coarse, anchor, scalars, peak, flush, record, history, rec, q, v):
    """Move the anchor (``anchor`` = (η, η̇, scratch, scratch), ``scalars`` = (t, F, F_low,
    pending coarse steps)) over the coarse steps ``peak`` [N] now proves free of a larger
    force (all if ``flush``), recording them. Returns (scalars, history, rec).
    """
    frequencies, force_row, _from_coupled = modes
    _every, length, cos_c, sin_c, low, margin = coarse
    eta_a, rate_a, eta_s, rate_s = anchor
    t_a, f_a, low_a, pending = scalars
    while pending > 0:
        _step(frequencies, eta_a, rate_a, cos_c, sin_c, eta_s, rate_s)
        low_s = _partial_force(force_row, eta_s, low)
        if not flush and max(low_a, low_s) + margin > peak:
            break
        f_s = _partial_force(force_row, eta_s, eta_s.shape[0])
        if record:
            history, rec = _record_step(modes, rows, (eta_a, rate_a), (eta_s, rate_s), t_a, length, f_s,
                                        history, rec, q, v)
        for k in range(eta_a.shape[0]):  # element loop: a slice assignment compiles for seconds
            eta_a[k] = eta_s[k]
            rate_a[k] = rate_s[k]
        t_a += length
        f_a = f_s
        low_a = low_s
        pending -= 1
    return (t_a, f_a, low_a, pending), history, rec


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _coarse_steps(modes, rows, coarse, limits, state, run, record, history, rec, q, v):
    """Coarse steps H from where the fine loop stopped, to the next fine window or the run's
    limits (provisional steps settled by :func:`_settle`). ``state`` = (η, η̇), ``run`` = (t,
    F, peak, peak time, steps). Returns (η, η̇, run, done, wi, vi, history, rec).
    """
    frequencies, force_row, from_coupled = modes
    _every, length, cos_c, sin_c, low, margin = coarse
    max_time, max_steps = limits
    eta, rate = state
    t, force, peak, peak_time, steps = run
    n = frequencies.shape[0]
    eta_next = np.empty(n)
    rate_next = np.empty(n)
    eta_a = np.empty(n)
    rate_a = np.empty(n)
    anchor = (eta_a, rate_a, np.empty(n), np.empty(n))
    low_now = _partial_force(force_row, eta, low)
    scalars = (t, force, low_now, 0)
    done = False
    while True:
        _step(frequencies, eta, rate, cos_c, sin_c, eta_next, rate_next)
        f_next = _partial_force(force_row, eta_next, n)
        low_next = _partial_force(force_row, eta_next, low)
        if min(low_now, low_next) <= margin:  # F may reach 0 in this step
            break
        steps += 1
        if f_next > peak:
            peak = f_next
            peak_time = t + length
        safe = max(low_now, low_next) + margin <= peak
        if scalars[3] > 0:
            scalars = (scalars[0], scalars[1], scalars[2], scalars[3] + 1)
        elif not safe:
            for k in range(n):  # element loop: a slice assignment compiles for seconds
                eta_a[k] = eta[k]
                rate_a[k] = rate[k]
            scalars = (t, force, low_now, 1)
        elif record:
            history, rec = _record_step(modes, rows, (eta, rate), (eta_next, rate_next), t, length, f_next,
                                        history, rec, q, v)
        eta, eta_next = eta_next, eta
        rate, rate_next = rate_next, rate
        t += length
        force = f_next
        low_now = low_next
        done = t >= max_time or steps >= max_steps
        if scalars[3] > 0:
            scalars, history, rec = _settle(modes, rows, coarse, anchor, scalars, peak, done, record, history, rec,
                                            q, v)
        if done or (safe and scalars[3] > 0):
            break
    if scalars[3] > 0:  # the window starts at the anchor
        eta, rate = eta_a, rate_a
        t, force = scalars[0], scalars[1]
    wi, vi = _to_physical(from_coupled, eta, rate, q, v)
    return eta, rate, (t, force, peak, peak_time, steps), done, wi, vi, history, rec


