"""The exact-step modal impact integrator (numba).

Between two instants the contact force is taken to vary linearly. For such a force
every modal coordinate ``q̈_j + 2ζ_jω_j q̇_j + ω_j² q_j = φ_j F(t)`` and the impactor
``m ẅ_i = −F`` are advanced *exactly* (:mod:`impactmaps.solvers.oscillator_step`), so no
mode limits the step by its own stability and the step follows the contact force, not
the highest mode. (The force is sampled once per step, and the sampled contact loop
itself is stable only while the highest coupled frequency turns well under half a
period per step: ``modal.STABLE_TOP_STEP``.)

One impact is a loop over four stages:

* **free flight** (no contact force): the step doubles up to 1024× as long as a bound on
  the closing speed proves that no touchdown fits inside it, and the run ends as soon as
  the gap exceeds the largest displacement the free vibration can reach at the impact
  point (:func:`_free_doublings`, :func:`_closing_speed_bound`). A recorded run takes the
  same steps and records the exact state at the end of each, and inside a step longer
  than 64 h every 64 h (:func:`_record_free_inside`), so its history rows are spaced up to
  64 h apart in free flight (every step h in contact) and its scalars are those of the
  run without a record;
* **event location**: contact start and separation are roots of the predicted gap
  inside the step (Brent's method); the step is cut there and the next one starts at the
  event (:mod:`impactmaps.solvers.contact_events`, :func:`_advance_to_event`);
* **step acceptance**: otherwise the force at the end of the step is found implicitly
  from the contact law (closed form for a linear law, safeguarded Newton otherwise), with
  the residual flexibility of the dropped modes in series with the contact, and the
  step is completed with it (:func:`_accept_step`);
* **peak tracking**: the largest force, refined by a parabola through three uniform
  samples (:func:`_track_peak`, :mod:`impactmaps.solvers._peak`).

Everything here is a plain function of arrays so one compiled kernel serves single
runs, batches and sweeps; :mod:`impactmaps.solvers.modal` is the Python front end.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..contact.base import KERNEL_TYPE
from ._peak import parabolic_peak
from .contact_events import locate_event, solve_end_force
from .coupled_contact import contact_phase
from .history_rows import HISTORY_WIDTH, record_row, structure_energy
from .lazy_kernel import LazyKernel
from .oscillator_step import (
    fill_step_coefficients,
    predict_step,
    propagate_free,
    square_free_propagators,
)

__all__ = ["integrate_impact"]

_F8 = numba.types.float64
_VECTOR = numba.types.Array(_F8, 1, "C")
_MATRIX = numba.types.Array(_F8, 2, "C")

#: Longest free-flight step: 2^(_FREE_POWERS − 1) = 1024 steps h. (Up to 2026-11-24 64 h:
#: a light impactor's long flights between re-impacts took ~30 % of a plate run's steps.)
_FREE_POWERS = 11
#: A recorded run's rows in free flight are at most 2^_RECORD_POWER = 64 steps h apart.
_RECORD_POWER = 6

# The stages below are plain compiled calls, not ``inline="always"``: numba's IR inlining
# adds reference-count operations on every array argument, which cost up to 1.5× per step
# (measured); only the helpers on scalars are inlined.


@numba.njit(cache=True)
def _no_reimpact_possible(omega, phi, q, v, wi, vi):
    """True once the impactor moves away and its gap exceeds the largest displacement the
    free vibration can ever reach at x0: |w_t| ≤ Σ|φ_j| sqrt(q_j² + (v_j/ω_j)²) (sum of
    modal amplitudes; damping only shrinks them), relative to the rigid-body motion.
    This bound is ≤ the spec's Cauchy–Schwarz bound sqrt(2 E_s Σφ²/ω²) (spec §3.6)."""
    rigid_w = 0.0
    rigid_v = 0.0
    bound = 0.0
    for j in range(q.shape[0]):
        if omega[j] == 0.0:
            rigid_w += phi[j] * q[j]
            rigid_v += phi[j] * v[j]
        else:
            bound += abs(phi[j]) * math.sqrt(q[j] * q[j] + (v[j] / omega[j]) ** 2)
    return vi - rigid_v <= 0.0 and wi - rigid_w < -bound


@numba.njit(cache=True)
def _damping_power(omega, zeta, v):
    power = 0.0
    for j in range(v.shape[0]):
        power += 2.0 * zeta[j] * omega[j] * v[j] * v[j]
    return power


@numba.njit(cache=True)
def _damping_work(omega, zeta, v, vn, length):
    """Work of the modal damping over a step of ``length`` [s] (trapezoidal rule)."""
    return 0.5 * length * (_damping_power(omega, zeta, v) + _damping_power(omega, zeta, vn))


@numba.njit(cache=True)
def _closing_speed_bound(omega, phi, q, v, vi):
    """Bound on the speed at which the gap can close in free flight [m/s]:
    ``|v_i| + Σ|φ_j| sqrt(ω_j² q_j² + v_j²)`` (modal amplitudes are constant or decay)."""
    speed_bound = abs(vi)
    for j in range(q.shape[0]):
        speed_bound += abs(phi[j]) * math.sqrt((omega[j] * q[j]) ** 2 + v[j] * v[j])
    return speed_bound


@numba.njit(cache=True)
def _free_doublings(phi, q, wi, h, speed_bound):
    """Free-flight stage: how many times the step h may double, k < ``_FREE_POWERS``.

    With no contact force every mode moves exactly over any step, so the step may grow
    as long as contact cannot start inside it: the gap −α shrinks at most at
    ``speed_bound`` V (:func:`_closing_speed_bound`), hence a step of 2^k h with
    2^k h V < −α cannot contain a touchdown.
    """
    wt_now = 0.0
    for j in range(q.shape[0]):
        wt_now += phi[j] * q[j]
    gap = wt_now - wi  # −α
    k = 0
    while k + 1 < _FREE_POWERS and (2.0 ** (k + 1)) * h * speed_bound < gap:
        k += 1
    return k


@numba.njit(cache=True)
def _record_free_inside(free_coef, k, h, t, wi, vi, residual, omega, phi, q, v, scratch, history, rec):
    """Record exact rows every 2^_RECORD_POWER h inside a free-flight step of 2^k h [s]
    that starts at time t [s] from the state (w_i, v_i, q, v), which is not touched;
    ``scratch`` is (4, n). Returns the history and the next row."""
    if k <= _RECORD_POWER:
        return history, rec
    spacing = 2.0**_RECORD_POWER * h
    q_a, v_a, q_b, v_b = scratch[0], scratch[1], scratch[2], scratch[3]
    for j in range(q.shape[0]):
        q_a[j] = q[j]
        v_a[j] = v[j]
    for i in range(1, 2 ** (k - _RECORD_POWER)):
        propagate_free(free_coef[_RECORD_POWER], spacing, wi, vi, q_a, v_a, phi, q_b, v_b)
        q_a, q_b = q_b, q_a
        v_a, v_b = v_b, v_a
        history, rec = record_row(history, rec, t + i * spacing, 0.0, wi + vi * (i * spacing), vi, residual,
                                  omega, phi, q_a, v_a)
    return history, rec


@numba.njit(cache=True)
def _advance_to_event(omega, zeta, phi, mass, wi, vi, q, v, force, s, ready, sub, qn, vn):
    """Event stage: advance over s with the force ramped to 0; modes into (qn, vn).

    ``ready`` says that ``sub`` already holds the step coefficients over s (left there by
    the event search). Returns the impactor displacement and velocity at the event.
    """
    if not ready:
        fill_step_coefficients(omega, zeta, phi, s, sub)
    wi_e, vi_e, _wt = predict_step(sub, s, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
    return wi_e, vi_e


@numba.njit(cache=True)
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


@numba.njit(cache=True)
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
def _out_of_time(t, steps, max_time, max_steps):
    """Whether the run has reached its time limit or its step budget."""
    return t >= max_time or steps >= max_steps


@numba.njit(cache=True, inline="always")
def _track_peak(peak, peak_time, f_prev2, f_prev1, force, t, h, uniform):
    """Peak-tracking stage after a step ending at t with ``force``.

    The largest sample, or the vertex of the parabola through the last three samples
    when they are uniform (h apart) and the middle one is a local maximum. Returns
    (peak, peak_time, f_prev2, f_prev1); the previous samples are reset across an event
    (−1 marks “no uniform sample”).
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


@numba.njit(cache=True)
def _step_compliance(coef, phi, h, mass, residual):
    """Compliance C [m/N] through which the end force of a step takes back indentation:
    impactor ``h²/(6m)``, residual flexibility and the retained modes ``Σ φ_j coef[5, j]``."""
    compliance = h * h / (6.0 * mass) + residual
    for j in range(phi.shape[0]):
        compliance += phi[j] * coef[5, j]
    return compliance


_ARGUMENTS = (
    KERNEL_TYPE, _VECTOR, _F8, _VECTOR, _VECTOR, _VECTOR, _F8, _F8, _F8, _F8, _F8,
    numba.types.boolean, numba.types.int64, _VECTOR, _VECTOR, _MATRIX, _MATRIX, _F8, _F8,
    numba.types.Array(numba.types.int64, 1, "C"),
)
#: The signatures of :data:`integrate_impact` by ``exact_phase`` (without / with the exact contact phase).
_SIGNATURES = {variant: numba.types.Tuple((_MATRIX, _MATRIX, _VECTOR))(*_ARGUMENTS, last)
               for variant, last in ((None, numba.types.none), (True, numba.types.boolean))}


def _exact_phase(args) -> bool | None:
    """The ``exact_phase`` argument for the other arguments: True when coupled modes are given."""
    return True if args[13].shape[0] > 0 else None


@numba.njit(cache=True, nogil=True)
def _integrate_impact(
    kernel,
    params,
    linear_stiffness,
    omega,
    phi,
    zeta,
    residual,
    mass,
    velocity,
    h,
    max_time,
    record,
    max_events,
    coupled_frequencies,
    coupled_force,
    from_coupled,
    to_coupled,
    contact_row_spacing,
    step_scale,
    stop,
    exact_phase,
):
    """Integrate one impact from first touch until re-impact is impossible.

    Parameters
    ----------
    kernel, params : contact-law kernel and its parameter vector.
    linear_stiffness : K [N/m] if the law is linear (closed-form contact solve), else 0.
    omega, phi, zeta : modal frequencies [rad/s], participations φ_j(x0), damping ratios.
    residual : residual compliance of dropped modes [m/N].
    mass, velocity : impactor mass [kg] and approach velocity [m/s].
    h : time step [s]; max_time : time limit [s].
    record : store the history at the end of every step (free-flight steps are the
        doubled ones, so rows are not uniformly spaced there); otherwise only scalars.
    max_events : capacity of the contact-interval table; a run with more contacts stops
        there, flagged like a run at its time limit (a sphere resting on a structure can
        otherwise chatter through millions of contacts of no force).
    coupled_frequencies, coupled_force, from_coupled, to_coupled : the coupled modes of a
        linear contact (:class:`~impactmaps.solvers.coupled_contact.CoupledModes`); when
        given (non-empty), every contact phase is propagated exactly through them
        (:func:`~impactmaps.solvers.coupled_contact.contact_phase`) and h serves free flight.
    contact_row_spacing, step_scale : longest spacing of recorded rows in an exact contact
        phase [s], and the factor on its step.
    stop : int64 array of one element; the run ends at its next step once another thread
        sets it non-zero (Ctrl-C, :func:`impactmaps.solvers.modal.simulate`); read only, it
        changes no arithmetic.
    exact_phase : None or True
        None: the variant without the exact contact phase (its branch is pruned when
        compiling, so :func:`~impactmaps.solvers.coupled_contact.contact_phase` is not
        compiled), for runs without coupled modes; True: with it (:data:`integrate_impact`).

    Returns
    -------
    history : (n_records, 8) array — t, F, α, w_i, v_i, w_t, v_t, E_structure.
    intervals : (n_intervals, 2) array of contact start/end times [s].
    scalars : array — peak force, time of peak, α_max, final impactor velocity,
        final structure energy, damping work, end time, time-limit-reached flag,
        steps taken, interval-table overflow flag.
    """
    n = omega.shape[0]
    coef = np.empty((8, n))
    fill_step_coefficients(omega, zeta, phi, h, coef)
    sub = np.empty((8, n))
    compliance_h = _step_compliance(coef, phi, h, mass, residual)
    damped = False  # a loop, not np.any(zeta > 0.0): the array expression compiles for longer
    for j in range(n):
        if zeta[j] > 0.0:
            damped = True

    q = np.zeros(n)
    v = np.zeros(n)
    qn = np.empty(n)
    vn = np.empty(n)
    q_try = np.empty(n)
    v_try = np.empty(n)
    t = 0.0
    wi = 0.0
    vi = velocity
    force = 0.0
    alpha_max = 0.0
    in_contact = False
    damping_work = 0.0

    max_steps = int(math.ceil(max_time / h)) + 2
    capacity = min(max_steps + 1, 4096) if record else 1
    history = np.zeros((capacity, HISTORY_WIDTH))
    intervals = np.zeros((max_events, 2))
    n_intervals = np.int64(0)
    overflow = 0.0
    rec = 0
    if record:
        history[0, 4] = velocity
        rec = 1

    peak = 0.0
    peak_time = 0.0
    f_prev2 = -1.0
    f_prev1 = -1.0
    hit_limit = 0.0
    steps = np.int64(0)  # not a literal 0: callees then compile for int64 only

    free_coef = np.empty((_FREE_POWERS, 4, n))  # homogeneous rows only: no force in flight
    record_scratch = np.empty((4, n if record else 0))
    free_ready = np.zeros(_FREE_POWERS, dtype=np.bool_)
    for row in range(4):  # element loops: a slice assignment compiles for seconds
        for j in range(n):
            free_coef[0, row, j] = coef[row, j]
    free_ready[0] = True
    speed_bound = -1.0  # < 0: to be computed at the next free-flight step
    starting = True  # the sphere touches the surface at t = 0 (and after each touchdown)
    coupled = False
    if exact_phase is not None:
        coupled = coupled_frequencies.shape[0] > 0
    while True:
        if stop[0] != 0:
            hit_limit = 1.0
            break
        if coupled and starting:
            if exact_phase is not None:  # typed None: this branch is not compiled
                touchdown = t
                before = steps
                t, wi, vi, force, peak, peak_time, steps, separated, history, rec = contact_phase(
                    coupled_frequencies, coupled_force, from_coupled, to_coupled, contact_row_spacing, step_scale,
                    omega, phi, residual, t, wi, vi, q, v, peak, peak_time, steps, max_time, max_steps,
                    record, history, rec)
                starting = False
                speed_bound = -1.0
                f_prev2 = -1.0
                f_prev1 = 0.0
                if steps > before:
                    n_intervals, full = _mark_contact(intervals, n_intervals, 0, touchdown)
                    overflow = max(overflow, full)
                    alpha_max = max(alpha_max, peak / linear_stiffness)
                    in_contact = not separated
                    if separated:
                        n_intervals, full = _mark_contact(intervals, n_intervals, 1, t)
                        overflow = max(overflow, full)
                if _out_of_time(t, steps, max_time, max_steps) or overflow > 0.0:
                    hit_limit = 1.0
                    break
                continue
        if force != 0.0 or starting:
            speed_bound = -1.0
        else:
            if speed_bound < 0.0:
                speed_bound = _closing_speed_bound(omega, phi, q, v, vi)
            # k > 0: the speed bound proves the long step free; k = 0: a free step whose
            # end shows no contact (the test the full step below would make)
            k = _free_doublings(phi, q, wi, h, speed_bound)
            length = (2.0 ** k) * h
            if not free_ready[k]:
                square_free_propagators(free_coef, free_ready, k)
            wi_free, wt_free = propagate_free(free_coef[k], length, wi, vi, q, v, phi, qn, vn)
            if k > 0 or solve_end_force(kernel, params, linear_stiffness, wi_free - wt_free,
                                        compliance_h, alpha_max) == 0.0:
                if damped:
                    damping_work += _damping_work(omega, zeta, v, vn, length)
                if record:
                    history, rec = _record_free_inside(free_coef, k, h, t, wi, vi, residual, omega, phi, q, v,
                                                       record_scratch, history, rec)
                wi = wi_free
                q, qn = qn, q
                v, vn = vn, v
                t += length
                steps += 1
                f_prev2 = -1.0
                f_prev1 = 0.0
                if record:
                    history, rec = record_row(history, rec, t, 0.0, wi, vi, residual, omega, phi, q, v)
                if (k > 0 or steps % 8 == 0) and _no_reimpact_possible(omega, phi, q, v, wi, vi):
                    break
                if _out_of_time(t, steps, max_time, max_steps):
                    hit_limit = 1.0
                    break
                continue
        # one step of h with the force going linearly from ``force`` to the implicit end
        # force; a contact event inside it cuts the step short at the event
        wi_p, vi_p, wt_p = predict_step(coef, h, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
        f_new = solve_end_force(kernel, params, linear_stiffness, wi_p - wt_p, compliance_h, alpha_max)
        separation, touchdown = _contact_event(force, f_new, starting)
        uniform = not (separation or touchdown)
        if uniform:
            wi, vi, wt = _accept_step(coef, h, mass, residual, compliance_h, f_new, wi_p, vi_p, wt_p, qn, vn)
            if damped:
                damping_work += _damping_work(omega, zeta, v, vn, h)
            q, qn = qn, q
            v, vn = vn, v
            if f_new > 0.0:
                if not in_contact:
                    in_contact = True
                    n_intervals, full = _mark_contact(intervals, n_intervals, 0, t)
                    overflow = max(overflow, full)
                alpha = wi - wt - residual * f_new
                if alpha > alpha_max:
                    alpha_max = alpha
            force = f_new
            starting = False
            t += h
        else:
            s, ready = locate_event(
                kernel, params, linear_stiffness, alpha_max, omega, zeta, phi, mass,
                wi, vi, q, v, force, wi_p - wt_p, separation, sub, q_try, v_try, h,
            )
            if s > 0.0:
                wi, vi = _advance_to_event(omega, zeta, phi, mass, wi, vi, q, v, force, s, ready, sub, qn, vn)
                if damped:
                    damping_work += _damping_work(omega, zeta, v, vn, s)
                q, qn = qn, q
                v, vn = vn, v
            if separation:
                n_intervals, full = _mark_contact(intervals, n_intervals, 1, t + s)
                overflow = max(overflow, full)
                in_contact = False
            else:
                starting = True  # contact begins at the start of the next step
            force = 0.0
            t += s  # the next step starts at the event, with the full step h
        steps += 1
        peak, peak_time, f_prev2, f_prev1 = _track_peak(peak, peak_time, f_prev2, f_prev1, force, t, h, uniform)
        if record:
            history, rec = record_row(history, rec, t, force, wi, vi, residual, omega, phi, q, v)
        if force == 0.0 and steps % 8 == 0 and _no_reimpact_possible(omega, phi, q, v, wi, vi):
            break
        if _out_of_time(t, steps, max_time, max_steps) or overflow > 0.0:
            hit_limit = 1.0
            break

    if in_contact:
        n_intervals, _full = _mark_contact(intervals, n_intervals, 1, t)
    scalars = np.empty(10)
    scalars[0] = peak
    scalars[1] = peak_time
    scalars[2] = alpha_max
    scalars[3] = vi
    scalars[4] = structure_energy(omega, q, v) + 0.5 * residual * force * force
    scalars[5] = damping_work
    scalars[6] = t
    scalars[7] = hit_limit
    scalars[8] = steps
    scalars[9] = overflow
    return history[:rec].copy(), intervals[:n_intervals].copy(), scalars


#: The integrator, called with the arguments of :func:`_integrate_impact` but
#: ``exact_phase``: the variant the arguments need is compiled on its first call, not at
#: import (:mod:`impactmaps.solvers.lazy_kernel`), so a run without coupled modes never
#: compiles the exact contact phase.
integrate_impact = LazyKernel(_integrate_impact, _SIGNATURES, _exact_phase)
