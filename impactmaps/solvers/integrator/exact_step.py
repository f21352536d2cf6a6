"""The exact-step modal impact integrator (numba).

Modes and impactor are advanced exactly for a force linear within each step, so the
step follows the contact force, not the highest mode; a loop over free flight, event
location, step acceptance and peak tracking (a linear law's contact phases exactly
through the coupled modes). The stages: docs/physics.rst, "The exact-step integrator".
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ...contact.base import KERNEL_TYPE
from ._peak import parabolic_peak
from .contact_events import locate_event, solve_end_force
from .coupled_contact import contact_phase
from .free_flight import (
    FREE_POWERS,
    damping_work,
    free_damping_work,
    free_doublings,
    no_reimpact_possible,
    out_of_time,
    record_free_inside,
)
from .history_rows import new_history, record_row, structure_energy, zeros_matrix
from .kernel_types import (
    COUPLED_TYPE,
    IMPACT_TYPE,
    MODES_TYPE,
    RUN_TYPE,
    SCALARS_TYPE,
    KernelScalars,
    Work,
)
from ..._compile import compile_helper
from ..._compile.lazy_kernel import LazyKernel
from .oscillator_step import fill_step_coefficients, predict_step, propagate_free, square_free_propagators

__all__ = ["integrate_impact", "callee_signatures"]

_MATRIX = numba.types.Array(numba.types.float64, 2, "C")
#: The columns of the contact-interval table, as int64 values (a literal 0 or 1 would compile
#: :func:`_mark_contact` once for each).
_START = np.int64(0)
_END = np.int64(1)
#: Contact phases in a row that may end no later than 10⁻⁹ h after the last one that moved
#: the time on (:func:`_progress`); the next such phase ends the run as stalled (``stalled``,
#: ``time_limit_reached``) rather than let it take zero-length steps up to its step budget.
STALL_LIMIT = 100

# The loop (:func:`_impact_loop`) keeps the step state in local variables and calls its
# per-step stages with arrays and scalars only: a stage that takes named tuples of arrays
# and is not simple enough for numba's reference-count pruning increfs and decrefs every
# array in them on each call (atomic operations: the named-tuple stages of before cost a
# cheap plate run 2× in its kernel, benchmarks/studies/RESULTS_kernel_speed.md). The per-step
# stages are plain compiled calls, not ``inline="always"``: numba's IR inlining adds
# reference-count operations on every array argument, which cost up to 1.5× per step
# (measured); only the helpers on scalars and the stages called once per run, per contact
# or per event (``_workspace``, ``_exact_contact``, ``_cut_at_event``, ``_finish``) are
# inlined. Functions only compiled code calls get no CPython or C wrapper
# (``no_cpython_wrapper``, ``no_cfunc_wrapper``): their named-tuple arguments made the
# wrappers a tenth of the integrator's cold compile.


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _advance_to_event(modes, mass, start, force, s, ready, sub, qn, vn):
    """Event stage: advance from ``start`` = (w_i, v_i, q, v) over s [s] with the force ramped
    from ``force`` [N] to 0, modes into (qn, vn) (``ready``: ``sub`` holds the coefficients
    over s); returns the impactor displacement [m] and velocity [m/s] at the event.
    """
    wi, vi, q, v = start
    omega, zeta, phi = modes.frequencies, modes.damping_ratios, modes.participation
    if not ready:
        fill_step_coefficients(omega, zeta, phi, s, sub)
    wi_e, vi_e, _wt = predict_step(sub, s, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
    return wi_e, vi_e


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _accept_step(coef, h, mass, residual, compliance_h, f_new, wi_p, vi_p, wt_p, qn, vn):
    """Step-acceptance stage: add the implicit end force ``f_new`` to the prediction made
    with the force ramped to 0 (modes in qn, vn); returns (w_i, v_i, w_t) at the end."""
    if f_new > 0.0:
        wt_p += f_new * (compliance_h - h * h / (6.0 * mass) - residual)
        wi_p -= h * h * f_new / (6.0 * mass)
        vi_p -= 0.5 * h * f_new / mass
        for j in range(qn.shape[0]):
            qn[j] += coef[5, j] * f_new
            vn[j] += coef[7, j] * f_new
    return wi_p, vi_p, wt_p


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _mark_contact(intervals, n_intervals, column, time):
    """Write a contact start (column 0) or end (column 1, which closes the interval) at
    ``time`` [s]; returns the interval count and 1.0 if the table was full (else 0.0)."""
    if n_intervals < intervals.shape[0]:
        intervals[n_intervals, column] = time
        return n_intervals + column, 0.0
    return n_intervals, 1.0


@numba.njit(cache=True, inline="always")
def _contact_event(force, f_new, starting):
    """(separation, touchdown) in a step whose force goes from ``force`` to ``f_new``;
    no touchdown is sought in the step that starts at a contact (``starting``)."""
    return force > 0.0 and f_new == 0.0, force == 0.0 and f_new > 0.0 and not starting


@numba.njit(cache=True, inline="always")
def _progress(t, t_mark, stalls, h):
    """Stall guard of the exact contact phase: (stalls, t_mark) after a phase that ended at
    t [s] (the next one must end 10⁻⁹ h [s] after ``t_mark``).
    """
    if t > t_mark:
        return np.int64(0), t + 1e-9 * h
    return stalls + 1, t_mark


@numba.njit(cache=True, inline="always")
def _track_peak(peak, peak_time, f_prev2, f_prev1, force, t, h, uniform):
    """Peak-tracking stage after a step ending at t [s] with ``force`` [N]: the largest
    sample, or the vertex of the parabola through three uniform samples; returns (peak,
    peak_time, f_prev2, f_prev1) (−1 marks “no uniform sample”).
    """
    if force > peak:
        peak = force
        peak_time = t
    if uniform and f_prev1 > 0.0 and f_prev2 > 0.0 and f_prev1 >= f_prev2 and f_prev1 >= force and force > 0.0:
        refined, shift = parabolic_peak(f_prev2, f_prev1, force)
        if refined > peak:
            peak = refined
            peak_time = t - h + shift * h
    if uniform:
        return peak, peak_time, f_prev1, force
    return peak, peak_time, -1.0, force


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _step_compliance(coef, phi, h, mass, residual):
    """Compliance C [m/N] through which the end force of a step takes back indentation:
    impactor ``h²/(6m)``, residual flexibility and the retained modes ``Σ φ_j coef[5, j]``."""
    compliance = h * h / (6.0 * mass) + residual
    for j in range(phi.shape[0]):
        compliance += phi[j] * coef[5, j]
    return compliance


@numba.njit(cache=True, inline="always")
def _workspace(modes, impact, run):
    """The :class:`~impactmaps.solvers.integrator.kernel_types.Work` of a run: its step coefficients,
    compliance and scratch arrays, the free-flight propagator over h and the
    contact-interval table."""
    omega, phi, zeta = modes.frequencies, modes.participation, modes.damping_ratios
    n = omega.shape[0]
    h = run.time_step
    coef = np.empty((8, n))
    fill_step_coefficients(omega, zeta, phi, h, coef)
    compliance_h = _step_compliance(coef, phi, h, impact.mass, modes.residual)
    damped = False  # a loop, not np.any(zeta > 0.0): the array expression compiles for longer
    for j in range(n):
        if zeta[j] > 0.0:
            damped = True
    free_coef = np.empty((FREE_POWERS, 4, n))  # homogeneous rows only: no force in flight
    free_ready = np.empty(FREE_POWERS, dtype=np.bool_)  # np.zeros would compile two more overloads
    for power in range(FREE_POWERS):
        free_ready[power] = power == 0
    for row in range(4):  # element loops: a slice assignment compiles for seconds
        for j in range(n):
            free_coef[0, row, j] = coef[row, j]
    max_steps = int(math.ceil(run.max_time / h)) + 2
    return Work(h, run.max_time, max_steps, run.record, compliance_h, damped, coef, np.empty((8, n)), np.empty(n),
                np.empty(n), free_coef, free_ready, np.empty((4, n if run.record else 0)),
                zeros_matrix(run.max_events, np.int64(2)))


@numba.njit(cache=True, inline="always")
def _exact_contact(coupled, modes, linear_stiffness, work, start, q, v, history, rec):
    """Exact contact stage: one contact phase through the coupled modes from the touchdown
    at ``start`` = (t, w_i, v_i, α_max, in contact, peak, peak time, steps, intervals
    written, overflow); q and v overwritten. Returns the same tuple with the force after
    v_i, then history, rec.
    """
    t0, wi, vi, alpha_max, in_contact, peak, peak_time, before, n_intervals, overflow = start
    t, wi, vi, force, peak, peak_time, steps, separated, history, rec = contact_phase(
        coupled, modes, (work.max_time, work.max_steps), (t0, wi, vi, peak, peak_time, before), q, v, work.record,
        history, rec)
    if steps > before:
        n_intervals, full = _mark_contact(work.intervals, n_intervals, _START, t0)
        overflow = max(overflow, full)
        alpha_max = max(alpha_max, peak / linear_stiffness)
        in_contact = not separated
        if separated:
            n_intervals, full = _mark_contact(work.intervals, n_intervals, _END, t)
            overflow = max(overflow, full)
    return (t, wi, vi, force, alpha_max, in_contact, peak, peak_time, steps, n_intervals, overflow), history, rec


@numba.njit(cache=True, inline="always")
def _cut_at_event(law, modes, mass, work, start, force, gap_end, separation):
    """Event stage of a sampled step from ``start`` = (w_i, v_i, q, v, qn, vn) with ``force``
    [N]: returns (s [s], swap, w_i, v_i, damping work over s [J]) of the separation or
    touchdown inside the step (``swap``: the state at s is in (qn, vn)).
    """
    kernel, params, linear_stiffness, alpha_max = law
    wi, vi, q, v, qn, vn = start
    s, ready = locate_event(kernel, params, linear_stiffness, alpha_max, modes, mass, (wi, vi, q, v), force,
                            gap_end, separation, (work.sub, work.q_try, work.v_try), work.h)
    swap = s > 0.0
    damping = 0.0
    if swap:
        wi, vi = _advance_to_event(modes, mass, (wi, vi, q, v), force, s, ready, work.sub, qn, vn)
        if work.damped:
            damping = damping_work(modes.frequencies, modes.damping_ratios, v, vn, s)
    return s, swap, wi, vi, damping


#: The signatures of :data:`integrate_impact` by ``exact_phase`` (without / with the exact contact phase).
_SIGNATURES = {variant: numba.types.Tuple((_MATRIX, _MATRIX, SCALARS_TYPE))(
    KERNEL_TYPE, numba.types.Array(numba.types.float64, 1, "C"), numba.types.float64, MODES_TYPE, IMPACT_TYPE,
    RUN_TYPE, COUPLED_TYPE, last)
    for variant, last in ((None, numba.types.none), (True, numba.types.boolean))}


def _exact_phase(args) -> bool | None:
    """The ``exact_phase`` argument for the other arguments: True when coupled modes are given."""
    return True if args[6].frequencies.shape[0] > 0 else None


@numba.njit(cache=True, nogil=True, no_cfunc_wrapper=True)
def _integrate_impact(kernel, params, linear_stiffness, modes, impact, run, coupled, exact_phase):
    """Integrate one impact from first touch until re-impact is impossible.

    ``kernel``, ``params``: the contact law; ``linear_stiffness``: K [N/m] of a linear law,
    else 0; ``modes``, ``impact``, ``run``, ``coupled``: the named tuples of
    :mod:`~impactmaps.solvers.integrator.kernel_types` (non-empty ``coupled``: every contact
    phase exact); ``exact_phase``: None compiles the variant without that phase, True with it.
    Returns ``history`` ((rows, 8): t, F, α, w_i, v_i, w_t, v_t, E_structure; at most
    ``run.max_rows``), ``intervals`` ((n, 2) contact start/end [s]) and :class:`KernelScalars`.
    """
    work = _workspace(modes, impact, run)
    history = new_history(min(work.max_steps + 1, 4096) if run.record else 1, run.max_rows)
    rec = 0
    if run.record:
        history.table[0, 4] = impact.velocity
        rec = 1
    n = modes.frequencies.shape[0]
    q = np.empty(n)  # at rest: zeros by a loop (np.zeros(n) compiles three more overloads than np.empty)
    v = np.empty(n)
    for j in range(n):
        q[j] = 0.0
        v[j] = 0.0
    state, hit_limit, swapped, history, rec = _impact_loop(kernel, params, linear_stiffness, modes, impact,
                                                          (q, v, np.empty(n), np.empty(n)), work, coupled,
                                                          exact_phase, (history, rec, run.stop))
    return _finish(modes, work, state, swapped, history, rec, hit_limit, run.record and rec >= run.max_rows)


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _impact_loop(kernel, params, linear_stiffness, modes, impact, modal, work, coupled, exact_phase, output):
    """The integrator's loop over its stages, the state in local variables. ``modal`` = (q, v,
    qn, vn), ``output`` = (history, rec, stop). Returns ((t, w_i, v_i, F, α_max, in contact,
    peak, peak time, steps, intervals written, overflow, damping work, stalled), hit_limit,
    (q, v), history, rec).
    """
    omega, phi, zeta, residual = modes.frequencies, modes.participation, modes.damping_ratios, modes.residual
    h, max_time, max_steps, record, compliance_h, damped = (work.h, work.max_time, work.max_steps, work.record,
                                                            work.compliance_h, work.damped)
    coef, free_coef, free_ready, intervals = work.coef, work.free_coef, work.free_ready, work.intervals
    q, v, qn, vn = modal
    history, rec, stop = output
    # the sphere touches the surface at t = 0 (``starting``); steps: int64, not a literal 0
    mass, vi = impact
    t, wi, force, alpha_max, in_contact, starting, damping = 0.0, 0.0, 0.0, 0.0, False, True, 0.0
    peak, peak_time, f_prev2, f_prev1, steps, n_intervals, overflow = 0.0, 0.0, -1.0, -1.0, np.int64(0), \
        np.int64(0), 0.0
    hit_limit, stalls, t_mark = False, np.int64(0), -1.0  # the stall guard (:func:`_progress`)
    speed_bound = -1.0  # < 0: to be computed at the next free-flight step
    exact = False
    if exact_phase is not None:
        exact = coupled.frequencies.shape[0] > 0
    while True:
        if stop[0] != 0:
            hit_limit = True
            break
        if exact and starting:
            if exact_phase is not None:  # typed None: this branch is not compiled
                (t, wi, vi, force, alpha_max, in_contact, peak, peak_time, steps, n_intervals, overflow), history, \
                    rec = _exact_contact(coupled, modes, linear_stiffness, work, (t, wi, vi, alpha_max, in_contact,
                                         peak, peak_time, steps, n_intervals, overflow), q, v, history, rec)
                starting, speed_bound, f_prev2, f_prev1 = False, -1.0, -1.0, 0.0
                stalls, t_mark = _progress(t, t_mark, stalls, h)
                if out_of_time(t, steps, max_time, max_steps) or overflow > 0.0 or stalls > STALL_LIMIT:
                    hit_limit = True
                    break
                if record and rec >= history.cap:
                    break
                continue
        free, swap = False, True
        if force != 0.0 or starting:
            speed_bound = -1.0
        else:
            # free flight: k > 0 doublings when the speed bound proves the long step free; k = 0
            # a free step whose end shows no contact (else the sampled step below takes it)
            k, speed_bound = free_doublings(omega, phi, q, v, wi, vi, h, speed_bound)
            length = (2.0 ** k) * h
            if not free_ready[k]:
                square_free_propagators(free_coef, free_ready, k)
            wi_free, wt_free = propagate_free(free_coef[k], length, wi, vi, q, v, phi, qn, vn)
            free = k > 0 or solve_end_force(kernel, params, linear_stiffness, wi_free - wt_free, compliance_h,
                                            alpha_max) == 0.0
        if free:
            if damped:
                damping += free_damping_work(omega, q, v, qn, vn)
            if record:
                history, rec = record_free_inside(free_coef, k, h, (t, wi, vi, q, v), modes, work.scratch, history,
                                                  rec)
            wi = wi_free
            t += length
            f_prev2, f_prev1 = -1.0, 0.0
            ended = k > 0 or (steps + 1) % 8 == 0  # re-impact may have become impossible
        else:  # a sampled step of h, the force linear from ``force`` to the implicit end force; a
            # contact event inside it cuts the step short at the event
            wi_p, vi_p, wt_p = predict_step(coef, h, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
            f_new = solve_end_force(kernel, params, linear_stiffness, wi_p - wt_p, compliance_h, alpha_max)
            separation, touchdown = _contact_event(force, f_new, starting)
            uniform = not (separation or touchdown)
            if uniform:
                wi, vi, wt = _accept_step(coef, h, mass, residual, compliance_h, f_new, wi_p, vi_p, wt_p, qn, vn)
                if damped:
                    damping += damping_work(omega, zeta, v, vn, h)
                if f_new > 0.0:
                    if not in_contact:
                        in_contact = True
                        n_intervals, full = _mark_contact(intervals, n_intervals, _START, t)
                        overflow = max(overflow, full)
                    alpha = wi - wt - residual * f_new
                    if alpha > alpha_max:
                        alpha_max = alpha
                force = f_new
                starting = False
                t += h
            else:
                s, swap, wi, vi, event_damping = _cut_at_event((kernel, params, linear_stiffness, alpha_max), modes,
                                                               mass, work, (wi, vi, q, v, qn, vn), force,
                                                               wi_p - wt_p, separation)
                if swap and damped:
                    damping += event_damping
                if separation:
                    n_intervals, full = _mark_contact(intervals, n_intervals, _END, t + s)
                    overflow = max(overflow, full)
                    in_contact = False
                else:
                    starting = True  # contact begins at the start of the next step
                force = 0.0
                t += s  # the next step starts at the event, with the full step h
            peak, peak_time, f_prev2, f_prev1 = _track_peak(peak, peak_time, f_prev2, f_prev1, force, t, h,
                                                            uniform)
            ended = force == 0.0 and (steps + 1) % 8 == 0
        steps += 1
        if swap:
            q, qn = qn, q
            v, vn = vn, v
        if record:
            history, rec = record_row(history, rec, t, 0.0 if free else force, wi, vi, residual, omega, phi, q, v)
        if ended and no_reimpact_possible(omega, phi, q, v, wi, vi):
            break
        if out_of_time(t, steps, max_time, max_steps) or overflow > 0.0:  # no overflow in flight
            hit_limit = True
            break
        if record and rec >= history.cap:
            break
    state = (t, wi, vi, force, alpha_max, in_contact, peak, peak_time, steps, n_intervals, overflow, damping,
             stalls > STALL_LIMIT)
    return state, hit_limit, (q, v), history, rec


@numba.njit(cache=True, inline="always")
def _finish(modes, work, state, modal, history, rec, hit_limit, row_cap):
    """The kernel's outputs at the end of a run (closing an open contact interval)."""
    t, _wi, vi, force, alpha_max, in_contact, peak, peak_time, steps, n_intervals, overflow, damping, stalled = state
    q, v = modal
    if in_contact:
        n_intervals, _full = _mark_contact(work.intervals, n_intervals, _END, t)
    energy = structure_energy(modes.frequencies, q, v) + 0.5 * modes.residual * force * force
    scalars = KernelScalars(peak, peak_time, alpha_max, vi, energy, damping, t, hit_limit or row_cap, steps,
                            overflow > 0.0, row_cap, stalled)
    return history.table[:rec].copy(), work.intervals[:n_intervals].copy(), scalars


#: The integrator, called with the arguments of :func:`_integrate_impact` but
#: ``exact_phase``: the variant the arguments need is compiled on its first call, not at
#: import (:mod:`impactmaps._compile.lazy_kernel`), so a run without coupled modes never
#: compiles the exact contact phase.
integrate_impact = LazyKernel(_integrate_impact, _SIGNATURES, _exact_phase)


def callee_signatures() -> dict:
    """``name → (dispatcher, argument types)`` of the integrator's callees the compile helper
    names: the exact signatures the integrator types them with.
    """
    from . import contact_events, free_flight, history_rows, oscillator_step

    f8, i8, flag = numba.types.float64, numba.types.int64, numba.types.boolean
    vector, matrix = numba.types.Array(f8, 1, "C"), numba.types.Array(f8, 2, "C")
    cube = numba.types.Array(f8, 3, "C")
    rows = numba.types.NamedTuple((matrix, i8), history_rows.HistoryRows)
    return {
        "fill_step_coefficients": (oscillator_step.fill_step_coefficients, (vector, vector, vector, f8, matrix)),
        "predict_step": (oscillator_step.predict_step, (matrix, f8, f8, f8, f8, vector, vector, vector, f8, f8,
                                                        vector, vector)),
        "free_doublings": (free_flight.free_doublings, (vector,) * 4 + (f8,) * 4),
        "square_free_propagators": (oscillator_step.square_free_propagators,
                                    (cube, numba.types.Array(flag, 1, "C"), i8)),
        "solve_end_force": (contact_events.solve_end_force, (KERNEL_TYPE, vector) + (f8,) * 4),
        "damping_work": (free_flight.damping_work, (vector,) * 4 + (f8,)),
        "record_free_inside": (free_flight.record_free_inside, (
            cube, i8, f8, numba.types.Tuple((f8, f8, f8, vector, vector)), MODES_TYPE, matrix, rows, i8)),
        "no_reimpact_possible": (free_flight.no_reimpact_possible, (vector,) * 4 + (f8, f8)),
        "locate_event": (contact_events.locate_event, (
            KERNEL_TYPE, vector, f8, f8, MODES_TYPE, f8, numba.types.Tuple((f8, f8, vector, vector)), f8, f8, flag,
            numba.types.Tuple((matrix, vector, vector)), f8)),
    }


compile_helper.register_integrator(integrate_impact, callee_signatures, __name__)
