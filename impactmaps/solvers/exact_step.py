"""The exact-step modal impact integrator (numba).

Between two instants the contact force is taken to vary linearly. For such a force
every modal coordinate ``q̈_j + 2ζ_jω_j q̇_j + ω_j² q_j = φ_j F(t)`` and the impactor
``m ẅ_i = −F`` are advanced *exactly*, so no mode limits the step by its own stability
and the step follows the contact force, not the highest mode. (The force is sampled
once per step, and the sampled contact loop itself is stable only while the highest
coupled frequency turns well under half a period per step:
``modal.STABLE_TOP_STEP``.) The force at the end of a step is found implicitly from
the contact law (closed form for a linear law, safeguarded Newton otherwise), with the
residual flexibility of the dropped modes in series with the contact. Contact start
and separation are roots of the predicted gap inside the step (Brent's method); the
step is cut there and the next one starts at the event. In free flight (scalars-only
runs) the step doubles up to 64× as long as a bound on the closing speed proves that
no touchdown fits inside it, and the run ends as soon as the gap exceeds the largest
displacement the free vibration can reach at the impact point.

Everything here is a plain function of arrays so one compiled kernel serves single
runs, batches and sweeps; :mod:`impactmaps.solvers.modal` is the Python front end.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..contact.base import KERNEL_TYPE

__all__ = ["oscillator_step_coefficients", "integrate_impact"]

_SERIES_LIMIT = 1.0


# Taylor coefficients in x² of sin x/x, (1 − cos x)/x² and (x − sin x)/x³ (ten terms:
# the first omitted one is below 3e-20 for x < 1), for Horner evaluation. Below
# _SERIES_LIMIT they replace sin and cos (no cancellation there, and three times faster).
_SINC = (1.0, -0.16666666666666666, 0.008333333333333333, -0.0001984126984126984, 2.7557319223985893e-06, -2.505210838544172e-08, 1.6059043836821613e-10, -7.647163731819816e-13, 2.8114572543455206e-15, -8.22063524662433e-18)
_COSC = (0.5, -0.041666666666666664, 0.001388888888888889, -2.48015873015873e-05, 2.755731922398589e-07, -2.08767569878681e-09, 1.1470745597729725e-11, -4.779477332387385e-14, 1.5619206968586225e-16, -4.110317623312165e-19)
_SIN3 = (0.16666666666666666, -0.008333333333333333, 0.0001984126984126984, -2.7557319223985893e-06, 2.505210838544172e-08, -1.6059043836821613e-10, 7.647163731819816e-13, -2.8114572543455206e-15, 8.22063524662433e-18, -1.9572941063391263e-20)


@numba.njit(cache=True)
def _horner10(c, x2):
    total = c[9]
    for k in range(8, -1, -1):
        total = c[k] + x2 * total
    return total


@numba.njit(cache=True)
def _trig_functions(x):
    """S = sin x/x, C1 = (1−cos x)/x², S3 = (x−sin x)/x³, stable for small x."""
    if x < _SERIES_LIMIT:
        x2 = x * x
        return _horner10(_SINC, x2), _horner10(_COSC, x2), _horner10(_SIN3, x2)
    sx = math.sin(x)
    inverse = 1.0 / x
    inverse2 = inverse * inverse
    return sx * inverse, (1.0 - math.cos(x)) * inverse2, (x - sx) * inverse2 * inverse


@numba.njit(cache=True)
def _expm4(a):
    """Matrix exponential of a 4×4 matrix by scaling and squaring with Taylor terms."""
    norm = 0.0
    for i in range(4):
        row = 0.0
        for j in range(4):
            row += abs(a[i, j])
        norm = max(norm, row)
    squarings = 0
    if norm > 0.25:
        squarings = int(math.ceil(math.log2(norm / 0.25)))
    scale = 2.0 ** (-squarings)
    scaled = a * scale
    result = np.eye(4)
    term = np.eye(4)
    for k in range(1, 14):
        term = term @ scaled / k
        result = result + term
    for _ in range(squarings):
        result = result @ result
    return result


@numba.njit(cache=True, inline="always")
def _undamped_coefficients(omega, h, s, c1, s3):
    """The eight step coefficients of an undamped mode from S, C1, S3 of ``_trig_functions``."""
    cosx = 1.0 - (omega * h) ** 2 * c1
    return (cosx, h * s, -omega * omega * h * s, cosx,
            h * h * (c1 - s3), h * h * s3, h * (s - c1), h * c1)


@numba.njit(cache=True)
def oscillator_step_coefficients(omega, zeta, h, out):
    """Exact one-step coefficients of ``q̈ + 2ζωq̇ + ω²q = f(t)``, f linear on [0, h].

    ``q(h) = out[0] q0 + out[1] v0 + out[4] f0 + out[5] f1`` and
    ``v(h) = out[2] q0 + out[3] v0 + out[6] f0 + out[7] f1``.
    Works for ω = 0 (free mass) and 0 ≤ ζ < 1.
    """
    if zeta == 0.0:
        s, c1, s3 = _trig_functions(omega * h)
        coefficients = _undamped_coefficients(omega, h, s, c1, s3)
        for k in range(8):
            out[k] = coefficients[k]
        return
    # damped: exponential of the augmented system [q, v, f, ḟ]
    m = np.zeros((4, 4))
    m[0, 1] = h
    m[1, 0] = -omega * omega * h
    m[1, 1] = -2.0 * zeta * omega * h
    m[1, 2] = h
    m[2, 3] = 1.0  # the last state holds d = f1 − f0, so ḟ = d/h and (ḟ)·h = d
    e = _expm4(m)
    out[0] = e[0, 0]
    out[1] = e[0, 1]
    out[2] = e[1, 0]
    out[3] = e[1, 1]
    out[4] = e[0, 2] - e[0, 3]
    out[5] = e[0, 3]
    out[6] = e[1, 2] - e[1, 3]
    out[7] = e[1, 3]


@numba.njit(cache=True)
def _fill_coefficients(omega, zeta, phi, h, coef):
    """Per-mode step coefficients into ``coef[k, j]`` (k = 0…7 as in
    :func:`oscillator_step_coefficients`); the force rows are pre-multiplied by φ_j.

    Undamped modes with ω_j h below ``_SERIES_LIMIT`` (all of them in a typical step)
    go through one branch-free loop that the compiler vectorises; the others through
    :func:`oscillator_step_coefficients`.
    """
    n = omega.shape[0]
    for j in range(n):
        x2 = (omega[j] * h) ** 2
        c = _undamped_coefficients(omega[j], h, _horner10(_SINC, x2), _horner10(_COSC, x2),
                                   _horner10(_SIN3, x2))
        coef[0, j] = c[0]
        coef[1, j] = c[1]
        coef[2, j] = c[2]
        coef[3, j] = c[3]
        coef[4, j] = c[4] * phi[j]
        coef[5, j] = c[5] * phi[j]
        coef[6, j] = c[6] * phi[j]
        coef[7, j] = c[7] * phi[j]
    tmp = np.empty(8)
    for j in range(n):
        if zeta[j] != 0.0 or not omega[j] * h < _SERIES_LIMIT:
            oscillator_step_coefficients(omega[j], zeta[j], h, tmp)
            for k in range(4):
                coef[k, j] = tmp[k]
            for k in range(4, 8):
                coef[k, j] = tmp[k] * phi[j]


_F8 = numba.types.float64
_VECTOR = numba.types.Array(_F8, 1, "C")
_MATRIX = numba.types.Array(_F8, 2, "C")


@numba.njit(_F8(KERNEL_TYPE, _VECTOR, _F8, _F8, _F8, _F8), cache=True)
def _solve_force(kernel, params, linear_stiffness, alpha_pred, compliance, alpha_max):
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


@numba.njit(cache=True, fastmath={"reassoc", "contract"})
def _predict(coef, h, mass, wi, vi, q, v, phi, f0, f1, qn, vn):
    """Advance impactor and modes over h with force f0 → f1; return (wi, vi, w_target).

    ``coef`` is (8, n): one row per coefficient, so the loop over modes reads contiguous
    memory, and re-association of the sum is allowed so that it vectorises (SIMD); the
    two together halve the cost of a step with hundreds of modes (benchmarks/RESULTS.md).
    """
    wt = 0.0
    for j in range(q.shape[0]):
        qj = coef[0, j] * q[j] + coef[1, j] * v[j] + coef[4, j] * f0 + coef[5, j] * f1
        vn[j] = coef[2, j] * q[j] + coef[3, j] * v[j] + coef[6, j] * f0 + coef[7, j] * f1
        qn[j] = qj
        wt += phi[j] * qj
    wi_new = wi + vi * h - h * h * (f0 / 3.0 + f1 / 6.0) / mass
    vi_new = vi - 0.5 * h * (f0 + f1) / mass
    return wi_new, vi_new, wt


@numba.njit(_F8(KERNEL_TYPE, _VECTOR, _F8, _F8, _F8), cache=True)
def _no_force_threshold(kernel, params, linear_stiffness, alpha_max, alpha_loaded):
    """Indentation α_f(α_max) at and below which the law gives no force [m].

    0 for elastic laws; the permanent indentation for plastic ones. Found by bisection
    on the kernel between α = 0 (never a force) and ``alpha_loaded`` (a force).
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


@numba.njit(cache=True)
def _ramp_gap(omega, zeta, phi, mass, wi, vi, q, v, force, s, sub, q_try, v_try):
    """Gap w_i − Σφ_j q_j after a sub-step s with the force ramped from ``force`` to 0."""
    _fill_coefficients(omega, zeta, phi, s, sub)
    wi_s, _vi_s, wt_s = _predict(sub, s, mass, wi, vi, q, v, phi, force, 0.0, q_try, v_try)
    return wi_s - wt_s


@numba.njit(cache=True)
def _locate_event(kernel, params, linear_stiffness, alpha_max, omega, zeta, phi, mass,
                  wi, vi, q, v, force, gap_end, separation, sub, q_try, v_try, h):
    """Time s ∈ [0, h] into the step at which contact ends (``separation``) or starts.

    The predicted gap g(s) (force ramped from its current value to 0 over s) crosses the
    no-force threshold α_f of the law. The root is bracketed by s = 0 and s = h
    (gap ``gap_end``) and found by Brent's method (inverse quadratic interpolation,
    secant and bisection steps; Brent 1973, the ``zeroin`` algorithm) to 1e-13 h: each
    evaluation costs one pass over the modes, and a handful replace the sixty of plain
    bisection. Returns s — on the no-contact side (g ≤ α_f) of the root, or where
    |g − α_f| ≤ 1e-11 of the bracket's gaps — and whether ``sub`` holds the step
    coefficients over s (the last point evaluated).
    """
    wt_now = 0.0
    for j in range(q.shape[0]):
        wt_now += phi[j] * q[j]
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
    small = 1e-11 * max(abs(fa), abs(fb))  # a gap this close to the threshold is the root
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
        fb = _ramp_gap(omega, zeta, phi, mass, wi, vi, q, v, force, b, sub, q_try, v_try) - threshold
        last = b
        if (fb > 0.0) == (fc > 0.0):
            c = a
            fc = fa
            d = b - a
            e = d
    # b and c bracket the root: the end with no force, or b if it is on the threshold
    root = b if (fb <= 0.0 or abs(fb) <= small) else c
    return root, root == last


@numba.njit(cache=True, fastmath={"reassoc", "contract"})
def _propagate_free(rows, h, wi, vi, q, v, phi, qn, vn):
    """Free flight over h (no contact force): impactor drifts, modes follow ``rows`` (4, n).

    Returns the impactor displacement and the target displacement Σ φ_j q_j at the end.
    """
    wt = 0.0
    for j in range(q.shape[0]):
        qj = rows[0, j] * q[j] + rows[1, j] * v[j]
        vn[j] = rows[2, j] * q[j] + rows[3, j] * v[j]
        qn[j] = qj
        wt += phi[j] * qj
    return wi + vi * h, wt


@numba.njit(cache=True)
def _square_free_propagators(free_coef, free_ready, k):
    """Free-vibration propagators over 2^k h from those over 2^(k−1) h, by squaring.

    Each mode's homogeneous step map [[c0, c1], [c2, c3]] over 2t is the square of the
    map over t (exact for damped modes too), so the doubled free-flight steps need no
    trigonometric functions. ``free_coef`` is (powers, 4, n).
    """
    for p in range(1, k + 1):
        if free_ready[p]:
            continue
        for j in range(free_coef.shape[2]):
            a = free_coef[p - 1, 0, j]
            b = free_coef[p - 1, 1, j]
            c = free_coef[p - 1, 2, j]
            d = free_coef[p - 1, 3, j]
            free_coef[p, 0, j] = a * a + b * c
            free_coef[p, 1, j] = a * b + b * d
            free_coef[p, 2, j] = c * a + d * c
            free_coef[p, 3, j] = c * b + d * d
        free_ready[p] = True

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
def _structure_energy(omega, q, v):
    energy = 0.0
    for j in range(q.shape[0]):
        energy += 0.5 * (v[j] * v[j] + omega[j] * omega[j] * q[j] * q[j])
    return energy


@numba.njit(cache=True)
def _damping_power(omega, zeta, v):
    power = 0.0
    for j in range(v.shape[0]):
        power += 2.0 * zeta[j] * omega[j] * v[j] * v[j]
    return power


@numba.njit(
    numba.types.Tuple((_MATRIX, _MATRIX, _VECTOR))(
        KERNEL_TYPE, _VECTOR, _F8, _VECTOR, _VECTOR, _VECTOR, _F8, _F8, _F8, _F8, _F8,
        numba.types.boolean, numba.types.int64,
    ),
    cache=True,
    nogil=True,
)
def integrate_impact(
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
    record : store the history at every step (otherwise only scalars).
    max_events : capacity of the contact-interval table.

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
    _fill_coefficients(omega, zeta, phi, h, coef)
    sub = np.empty((8, n))
    compliance_h = h * h / (6.0 * mass) + residual
    for j in range(n):
        compliance_h += phi[j] * coef[5, j]
    damped = False
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
    history = np.zeros((capacity, 8))
    intervals = np.zeros((max_events, 2))
    n_intervals = 0
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
    steps = 0

    # Free flight: with no contact force every mode moves exactly over any step, so the
    # step may grow as long as contact cannot start inside it: the gap −α shrinks at most
    # at V = |v_i| + Σ|φ_j| sqrt(ω_j² q_j² + v_j²) (amplitudes are constant or decaying),
    # hence a step of k·h with k·h·V < −α cannot contain a touchdown (k a power of 2).
    powers = 7
    free_coef = np.empty((powers, 4, n))  # homogeneous rows only: no force in flight
    free_ready = np.zeros(powers, dtype=np.bool_)
    free_coef[0] = coef[:4]
    free_ready[0] = True
    speed_bound = -1.0  # < 0: to be computed at the next free-flight step
    starting = True  # the sphere touches the surface at t = 0 (and after each touchdown)
    while True:
        if force == 0.0 and not starting:
            if speed_bound < 0.0:
                speed_bound = abs(vi)
                for j in range(n):
                    speed_bound += abs(phi[j]) * math.sqrt((omega[j] * q[j]) ** 2 + v[j] * v[j])
            wt_now = 0.0
            for j in range(n):
                wt_now += phi[j] * q[j]
            gap = wt_now - wi  # −α
            k = 0
            while k + 1 < powers and (2.0 ** (k + 1)) * h * speed_bound < gap:
                k += 1
            if not record:
                # k > 0: the speed bound proves the long step free; k = 0: a free step
                # whose end shows no contact (the test the full step below would make)
                big = (2.0 ** k) * h
                if not free_ready[k]:
                    _square_free_propagators(free_coef, free_ready, k)
                wi_free, wt_free = _propagate_free(free_coef[k], big, wi, vi, q, v, phi, qn, vn)
                if k > 0 or _solve_force(kernel, params, linear_stiffness, wi_free - wt_free,
                                         compliance_h, alpha_max) == 0.0:
                    wi = wi_free
                    if damped:
                        damping_work += 0.5 * big * (_damping_power(omega, zeta, v) + _damping_power(omega, zeta, vn))
                    q, qn = qn, q
                    v, vn = vn, v
                    t += big
                    steps += 1
                    f_prev2 = -1.0
                    f_prev1 = 0.0
                    if (k > 0 or steps % 8 == 0) and _no_reimpact_possible(omega, phi, q, v, wi, vi):
                        break
                    if t >= max_time or steps >= max_steps:
                        hit_limit = 1.0
                        break
                    continue
        else:
            speed_bound = -1.0
        # one step of h with the force going linearly from ``force`` to the implicit end
        # force; a contact event inside it cuts the step short at the event
        uniform = True
        advanced = h
        wi_p, vi_p, wt_p = _predict(coef, h, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
        f_new = _solve_force(kernel, params, linear_stiffness, wi_p - wt_p, compliance_h, alpha_max)
        separation = force > 0.0 and f_new == 0.0
        touchdown = force == 0.0 and f_new > 0.0 and not starting
        if separation or touchdown:
            uniform = False
            s, ready = _locate_event(
                kernel, params, linear_stiffness, alpha_max, omega, zeta, phi, mass,
                wi, vi, q, v, force, wi_p - wt_p, separation, sub, q_try, v_try, h,
            )
            if s > 0.0:
                if not ready:
                    _fill_coefficients(omega, zeta, phi, s, sub)
                wi_e, vi_e, _wt = _predict(sub, s, mass, wi, vi, q, v, phi, force, 0.0, qn, vn)
                if damped:
                    damping_work += 0.5 * s * (
                        _damping_power(omega, zeta, v) + _damping_power(omega, zeta, vn)
                    )
                wi = wi_e
                vi = vi_e
                q, qn = qn, q
                v, vn = vn, v
            if separation:
                if n_intervals < max_events:
                    intervals[n_intervals, 1] = t + s
                    n_intervals += 1
                else:
                    overflow = 1.0
                in_contact = False
            else:
                starting = True  # contact begins at the start of the next step
            force = 0.0
            advanced = s  # the next step starts at the event, with the full step h
        else:
            # no event: accept the step with the implicit end force
            if f_new > 0.0:
                wt_p += f_new * (compliance_h - h * h / (6.0 * mass) - residual)
                wi_p -= h * h * f_new / (6.0 * mass)
                vi_p -= 0.5 * h * f_new / mass
                for j in range(n):
                    qn[j] += coef[5, j] * f_new
                    vn[j] += coef[7, j] * f_new
            if damped:
                damping_work += 0.5 * h * (
                    _damping_power(omega, zeta, v) + _damping_power(omega, zeta, vn)
                )
            wi = wi_p
            vi = vi_p
            q, qn = qn, q
            v, vn = vn, v
            if f_new > 0.0:
                if not in_contact:
                    in_contact = True
                    if n_intervals < max_events:
                        intervals[n_intervals, 0] = t
                    else:
                        overflow = 1.0
                alpha = wi - wt_p - residual * f_new
                if alpha > alpha_max:
                    alpha_max = alpha
            force = f_new
            starting = False
        t += advanced
        steps += 1

        # peak tracking with parabolic refinement on uniform samples
        if force > peak:
            peak = force
            peak_time = t
        if uniform and f_prev1 > 0.0 and f_prev2 > 0.0 and f_prev1 >= f_prev2 and f_prev1 >= force and force > 0.0:
            denom = f_prev2 - 2.0 * f_prev1 + force
            if denom < 0.0:
                shift = 0.5 * (f_prev2 - force) / denom
                refined = f_prev1 - 0.25 * (f_prev2 - force) * shift
                if refined > peak:
                    peak = refined
                    peak_time = t - h + shift * h
        if uniform:
            f_prev2 = f_prev1
            f_prev1 = force
        else:
            f_prev2 = -1.0
            f_prev1 = force

        if record:
            wt = residual * force
            vt = 0.0
            for j in range(n):
                wt += phi[j] * q[j]
                vt += phi[j] * v[j]
            if rec == history.shape[0]:
                grown = np.zeros((2 * history.shape[0], 8))
                grown[:rec] = history
                history = grown
            history[rec, 0] = t
            history[rec, 1] = force
            history[rec, 2] = wi - wt
            history[rec, 3] = wi
            history[rec, 4] = vi
            history[rec, 5] = wt
            history[rec, 6] = vt
            history[rec, 7] = _structure_energy(omega, q, v) + 0.5 * residual * force * force
            rec += 1

        if force == 0.0 and steps % 8 == 0 and _no_reimpact_possible(omega, phi, q, v, wi, vi):
            break
        if t >= max_time or steps >= max_steps:
            hit_limit = 1.0
            break

    if in_contact and n_intervals < max_events:
        intervals[n_intervals, 1] = t
        n_intervals += 1
    scalars = np.empty(10)
    scalars[0] = peak
    scalars[1] = peak_time
    scalars[2] = alpha_max
    scalars[3] = vi
    scalars[4] = _structure_energy(omega, q, v) + 0.5 * residual * force * force
    scalars[5] = damping_work
    scalars[6] = t
    scalars[7] = hit_limit
    scalars[8] = steps
    scalars[9] = overflow
    return history[:rec].copy(), intervals[:n_intervals].copy(), scalars
