"""The contact force at the end of a step and the instants where contact starts or ends.

The end force solves ``F1 = F(α_pred − C F1; α_max)`` (closed form for a linear law,
safeguarded Newton otherwise); a contact event is where the gap predicted with the force
ramped to zero crosses the law's no-force indentation (Brent's method).
"""

from __future__ import annotations

import numba

from .oscillator_step import fill_step_coefficients, predict_step

__all__ = ["locate_event", "solve_end_force"]


@numba.njit(cache=True, no_cfunc_wrapper=True)
def solve_end_force(kernel, params, linear_stiffness, alpha_pred, compliance, alpha_max):
    """Force F1 ≥ 0 with F1 = F(α_pred − C F1; α_max) (monotone, unique root).

    ``linear_stiffness > 0`` marks a linear law: closed form, no kernel call.
    """
    if linear_stiffness > 0.0:
        if alpha_pred <= 0.0:
            return 0.0
        return linear_stiffness * alpha_pred / (1.0 + linear_stiffness * compliance)
    f_trial, k_trial = kernel(alpha_pred, alpha_max, params)
    if f_trial <= 0.0:
        return 0.0
    lo = 0.0
    hi = f_trial
    force = f_trial / (1.0 + k_trial * compliance)
    for _ in range(100):
        alpha = alpha_pred - compliance * force
        f, k = kernel(alpha, alpha_max, params)
        g = force - f
        if g > 0.0:
            hi = force
        else:
            lo = force
        if abs(g) <= 1e-14 * f_trial:
            return force
        step = g / (1.0 + k * compliance)
        candidate = force - step
        if candidate <= lo or candidate >= hi:
            candidate = 0.5 * (lo + hi)
        if hi - lo <= 1e-15 * f_trial:
            return candidate
        force = candidate
    return force


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _no_force_threshold(kernel, params, linear_stiffness, alpha_max, alpha_loaded):
    """Indentation α_f(α_max) [m] at and below which the law gives no force (0 for elastic laws),
    by bisection between 0 and ``alpha_loaded``.
    """
    if linear_stiffness > 0.0:
        return 0.0
    lo = 0.0
    hi = alpha_loaded
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        f, _k = kernel(mid, alpha_max, params)
        if f > 0.0:
            hi = mid
        else:
            lo = mid
        if hi - lo <= 1e-15 * alpha_loaded:
            break
    return lo


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _ramp_gap(modes, mass, state, force, s, work):
    """Gap w_i − Σφ_j q_j after a sub-step s [s] with the force ramped from ``force`` [N] to
    0, from ``state`` = (w_i, v_i, q, v); ``work`` = (sub, q_try, v_try): the step
    coefficients over s and the modal state at its end are written there."""
    wi, vi, q, v = state
    sub, q_try, v_try = work
    phi = modes.participation
    fill_step_coefficients(modes.frequencies, modes.damping_ratios, phi, s, sub)
    wi_s, _vi_s, wt_s = predict_step(sub, s, mass, wi, vi, q, v, phi, force, 0.0, q_try, v_try)
    return wi_s - wt_s


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def locate_event(kernel, params, linear_stiffness, alpha_max, modes, mass, state, force, gap_end, separation,
                 work, h):
    """Time s ∈ [0, h] into the step at which contact ends (``separation``) or starts, by
    Brent's method on the predicted gap minus the no-force indentation (to 1e-13 h); the law
    (``kernel``, ``params``, ``linear_stiffness``) at ``alpha_max`` [m], ``state`` = (w_i,
    v_i, q, v) and ``force`` [N] at the step's start, ``gap_end`` [m] at its end. Returns s
    and whether ``sub`` holds the step coefficients over s.
    """
    wi, vi, q, v = state
    phi = modes.participation
    wt_now = 0.0
    vt_now = 0.0
    for j in range(q.shape[0]):
        wt_now += phi[j] * q[j]
        vt_now += phi[j] * v[j]
    gap_now = wi - wt_now
    loaded = gap_now if separation else gap_end
    threshold = _no_force_threshold(kernel, params, linear_stiffness, alpha_max, loaded)
    a = 0.0
    fa = gap_now - threshold  # > 0 for a separation, ≤ 0 for a touchdown
    b = h
    fb = gap_end - threshold
    if fa == 0.0 or fb == 0.0 or (fa > 0.0) == (fb > 0.0):
        return (h if separation else 0.0), False  # degenerate bracket: the step edge
    tol = 1e-13 * h
    eps = 2.220446049250313e-16
    small = 1e-11 * max(abs(fa), abs(fb))  # a gap this close to the threshold is the root …
    if not separation and -fa <= small and vi < vt_now:
        # … but not the start of a touchdown's step where the gap opens: a state just past a
        # separation, still touching to round-off, is not the next touchdown (taking it would
        # find that separation again and no time would pass: tests/solvers/test_graze_spin.py)
        small = -0.5 * fa
    last = -1.0  # the point whose coefficients ``sub`` holds
    c = a
    fc = fa
    d = b - a
    e = d
    for _ in range(200):
        if abs(fc) < abs(fb):
            a, b, c = b, c, b
            fa, fb, fc = fb, fc, fb
        tol1 = 2.0 * eps * abs(b) + 0.5 * tol
        xm = 0.5 * (c - b)
        if abs(xm) <= tol1 or abs(fb) <= small:
            break
        if abs(e) >= tol1 and abs(fa) > abs(fb):
            ratio = fb / fa
            if a == c:  # secant
                p = 2.0 * xm * ratio
                qq = 1.0 - ratio
            else:  # inverse quadratic interpolation
                qa = fa / fc
                rb = fb / fc
                p = ratio * (2.0 * xm * qa * (qa - rb) - (b - a) * (rb - 1.0))
                qq = (qa - 1.0) * (rb - 1.0) * (ratio - 1.0)
            if p > 0.0:
                qq = -qq
            p = abs(p)
            if 2.0 * p < min(3.0 * xm * qq - abs(tol1 * qq), abs(e * qq)):
                e = d
                d = p / qq
            else:
                d = xm
                e = d
        else:
            d = xm
            e = d
        a = b
        fa = fb
        if abs(d) > tol1:
            b += d
        else:
            b += tol1 if xm > 0.0 else -tol1
        fb = _ramp_gap(modes, mass, state, force, b, work) - threshold
        last = b
        if (fb > 0.0) == (fc > 0.0):
            c = a
            fc = fa
            d = b - a
            e = d
    # b and c bracket the root: the end with no force, or b if it is on the threshold
    root = b if (fb <= 0.0 or abs(fb) <= small) else c
    return root, root == last
