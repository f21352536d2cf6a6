"""Exact propagation of a linear contact phase through the coupled modes (numba).

While a *linear* contact ``F = K α`` is closed, impactor, contact spring (in series with
the residual compliance r of the dropped modes, ``K_e = K/(1 + K r)``) and the retained
undamped modes form one linear system,

    M ẍ + K_c x = 0,   x = (w_i, q_1 … q_n),   M = diag(m_i, 1 … 1),
    K_c = diag(0, ω_1² … ω_n²) + K_e g gᵀ,   g = (1, −φ_1 … −φ_n),

with the contact force ``F = K_e gᵀ x``. ``K_c`` is positive definite (every ω_j > 0 and
``g`` has a component on the impactor), so with ``M^{-1/2} K_c M^{-1/2} = U Ω² Uᵀ`` the
coupled coordinates ``η = Uᵀ M^{1/2} x`` move as independent undamped oscillators and

    F(t) = Σ_k c_k (η_k cos Ω_k t + (η̇_k/Ω_k) sin Ω_k t),   c = K_e gᵀ M^{-1/2} U,

exactly, for any step. The contact phase then needs no stability limit and no force
interpolation: the step only has to *sample* F(t) finely enough to see its peak and its
end, which are then located on the closed form (the root of F' by the Illinois method
for the peak, the root of F for the separation). The step follows the content of the
force at the start of each contact, amplitude ``A_k = |c_k| sqrt(η_k² + (η̇_k/Ω_k)²)`` per
coupled mode: the fastest modes whose amplitudes sum to at most ε/2 of ``Σ A_k``
(:data:`CONTACT_RESOLUTION` ε) are left unsampled, every other mode is sampled at
``Ω_k h ≤ 1`` and the mode of largest amplitude at ``Ω_k h ≤`` :data:`SAMPLED_PHASE`
(times the settings' step scale; a recorded run adds exact rows inside the steps). The peak is located on
the sampled modes and evaluated with all of them, so what the unsampled ripple can move
the peak by is at most ``2 Σ_unsampled A_k ≤ ε Σ A_k``. This is what answers the quasi-static corner (heavy impactor, soft contact): there
the modes the mode floor keeps lie far above the contact frequency and forced the
sampled scheme of :mod:`impactmaps.solvers.exact_step` to ~10⁷ steps per contact.

Two rates. That fine step h is only needed near the peak and near the separation;
elsewhere the phase takes coarse steps H = N h, N the whole number of fine steps in the
content step of :data:`COARSE_RESOLUTION` (no step scale: H does not change the result),
when N ≥ :data:`COARSE_FACTOR` (else it keeps h throughout, exactly the single-rate
loop). The amplitudes A_k are constant through a contact, so with F_low the force of the
coupled modes with Ω_k H ≤ 1, ``B`` the A_k of the others and ``m = H²/8 Σ_low A_k Ω_k²``
(the chord error of F_low), F anywhere in a coarse step lies within ``B + m`` of the
range of the two F_low samples. A coarse step is taken only where that proves no instant
in it has F ≤ 0 and none has F above the peak already found (provisionally, while later
samples may still raise that peak enough); every other stretch is scanned at h from a
coarse sample, the sample before it recomputed exactly, until a sample from which the
coarse step is proven again. The coarse samples lie on the fine grid, so the fine
windows see the samples, sampled maxima and first sample with F ≤ 0 of the single-rate
loop, and every candidate of the peak it would find in a coarse step is below the peak
found: the two-rate phase returns the single-rate peak, peak time and separation up to
round-off (the fast modes reach a sample along another path: ≤ 2·10⁻¹⁴ relative in one
contact, ~10⁻¹¹ after the 144 chattering contacts of a quasi-static map point, measured),
with 8–11× fewer steps at the finest level of the quasi-static map points (3–4× less CPU
for a whole point). (A run that ends at its time limit in contact may overrun it by one
coarse step.)

Free flight between contacts stays with :mod:`impactmaps.solvers.exact_step` (exact
there already); :func:`coupled_modes` says when this phase applies (undamped modes, all
ω_j > 0, linear law).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from .._checks import require_positive
from ..targets.base import ModalBasis
from .history_rows import record_row

__all__ = ["COARSE_FACTOR", "COARSE_RESOLUTION", "CONTACT_RESOLUTION", "SAMPLED_PHASE", "CoupledModes",
           "contact_phase", "coupled_modes"]

#: ε of the contact-phase step rule: coupled modes whose force amplitudes sum to at most
#: ε/2 of the force content are not sampled (module docstring) [-].
CONTACT_RESOLUTION = 1e-5
#: ε of the coarse step of a two-rate contact phase (module docstring): the coupled
#: modes whose amplitudes sum to at most ε/2 of the force content set no coarse step
#: (3e-3: fewest steps over the quasi-static map points of the beam and the plate
#: against 1e-3, 5e-3, 1e-2 and 3e-2) [-].
COARSE_RESOLUTION = 3e-3
#: Fewest fine steps in a coarse step: below, the contact phase keeps the fine step
#: (2: 12 % less CPU than 4 over the quasi-static map points of the beam and the plate) [-].
COARSE_FACTOR = 2
#: Largest Ω_k h of the coupled mode that carries the most force (25 samples per period) [rad].
SAMPLED_PHASE = 0.25
#: Iterations of the Illinois root searches (each halves the bracket at least every
#: third iteration; 200 reach round-off from any bracket).
_ROOT_ITERATIONS = 200


@dataclass(frozen=True)
class CoupledModes:
    """The coupled modes of impactor + linear contact + retained modes.

    Attributes
    ----------
    frequencies : ndarray, shape (n + 1,)
        Ω_k [rad/s], ascending.
    force_row : ndarray, shape (n + 1,)
        c_k [N/m·sqrt(kg)]: ``F = Σ c_k η_k``.
    from_coupled : ndarray, shape (n + 1, n + 1)
        ``x = from_coupled @ η`` (x = (w_i, q_1 … q_n)).
    to_coupled : ndarray, shape (n + 1, n + 1)
        ``η = to_coupled @ x``.
    """

    frequencies: np.ndarray
    force_row: np.ndarray
    from_coupled: np.ndarray
    to_coupled: np.ndarray


def coupled_modes(basis: ModalBasis, contact_stiffness: float, impactor_mass: float) -> CoupledModes | None:
    """The coupled modes of a linear contact phase, or ``None`` where they do not apply.

    Parameters
    ----------
    basis : ModalBasis
        Retained modes (mass-normalised participations φ_j [1/sqrt(kg)]) and residual
        compliance r [m/N].
    contact_stiffness : float
        K [N/m] of the linear law.
    impactor_mass : float
        m_i [kg].

    Returns
    -------
    CoupledModes or None
        ``None`` for damped modes or rigid-body modes (ω_j = 0): the phase is then left
        to the sampled scheme.
    """
    require_positive("contact_stiffness", contact_stiffness, "N/m")
    require_positive("impactor_mass", impactor_mass, "kg")
    if (basis.damping_ratios > 0.0).any() or (basis.frequencies <= 0.0).any():
        return None
    effective = contact_stiffness / (1.0 + contact_stiffness * basis.residual_compliance)
    gvec = np.concatenate(([1.0], -basis.participation))
    scale = np.concatenate(([1.0 / np.sqrt(impactor_mass)], np.ones(basis.size)))
    scaled = (scale * gvec)  # M^{-1/2} g
    stiffness = effective * np.outer(scaled, scaled)
    stiffness.flat[:: basis.size + 2] += np.concatenate(([0.0], basis.frequencies**2))  # the diagonal
    eigenvalues, vectors = np.linalg.eigh(stiffness)
    if not eigenvalues[0] > 0.0:
        return None
    from_coupled = scale[:, None] * vectors
    to_coupled = np.ascontiguousarray(vectors.T / scale[None, :])
    force_row = effective * (gvec @ from_coupled)
    return CoupledModes(np.sqrt(eigenvalues), np.ascontiguousarray(force_row),
                        np.ascontiguousarray(from_coupled), to_coupled)


@numba.njit(cache=True)
def _force(frequencies, force_row, eta, rate, s):
    """F(s) [N] a time s [s] after the state (η, η̇)."""
    total = 0.0
    for k in range(eta.shape[0]):
        x = frequencies[k] * s
        total += force_row[k] * (eta[k] * math.cos(x) + rate[k] / frequencies[k] * math.sin(x))
    return total


@numba.njit(cache=True)
def _force_rate(frequencies, force_row, eta, rate, s, count):
    """dF/dt(s) [N/s] a time s [s] after the state (η, η̇), of the first ``count``
    coupled modes (the sampled ones: the peak search leaves out the ripple of modes the
    step does not resolve, whose derivative would dominate)."""
    total = 0.0
    for k in range(count):
        x = frequencies[k] * s
        total += force_row[k] * (rate[k] * math.cos(x) - eta[k] * frequencies[k] * math.sin(x))
    return total


@numba.njit(cache=True)
def _root(frequencies, force_row, eta, rate, start, length, derivative, count):
    """Root in (start, length) of F (or, if ``derivative``, of the rate of its first
    ``count`` coupled modes) from the state (η, η̇), given a sign change over the interval
    (Illinois method) [s]."""
    a = start
    b = length
    if derivative:
        fa = _force_rate(frequencies, force_row, eta, rate, a, count)
        fb = _force_rate(frequencies, force_row, eta, rate, b, count)
    else:
        fa = _force(frequencies, force_row, eta, rate, a)
        fb = _force(frequencies, force_row, eta, rate, b)
    side = 0
    for _ in range(_ROOT_ITERATIONS):
        if fa == fb:
            break
        c = (a * fb - b * fa) / (fb - fa)
        if not (a < c < b):
            c = 0.5 * (a + b)
        fc = _force_rate(frequencies, force_row, eta, rate, c, count) if derivative else \
            _force(frequencies, force_row, eta, rate, c)
        if (fc > 0.0) == (fa > 0.0):
            a, fa = c, fc
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb = c, fc
            if side == 1:
                fa *= 0.5
            side = 1
        if b - a <= 1e-14 * length or fc == 0.0:
            break
    # F: the end of the bracket where F ≤ 0 (the state after a separation has no force);
    # F': its middle
    return 0.5 * (a + b) if derivative else b


@numba.njit(cache=True)
def _first_positive(frequencies, force_row, eta, rate, length):
    """An instant in (0, length] [s] where F > 0, by halving from ``length``; 0 if none
    is found down to length/2⁶⁰ (the force of a contact that begins tangentially grows
    as ½ F''(0) s²)."""
    s = length
    for _ in range(60):
        if _force(frequencies, force_row, eta, rate, s) > 0.0:
            return s
        s *= 0.5
    return 0.0


@numba.njit(cache=True)
def _clear_gap(from_coupled, frequencies, eta, rate, phi, s, length, eta_s, rate_s, q, v):
    """The separation instant ``s`` [s], moved later by the least round-off amount that
    makes the physical gap w_i − Σ φ_j q_j strictly open; returns it with w_i [m] and
    v_i [m/s] there (the modes' state in q, v; the coupled state in η_s, η̇_s).

    F(s) ≤ 0 on the closed form does not guarantee it in the physical coordinates, whose
    difference cancels; a gap left at +0 would make the free flight's touchdown search
    find the same instant again (a degenerate bracket) and the run would ping-pong
    between contact and flight without advancing.
    """
    shift = 1e-14 * length
    wi = 0.0
    vi = 0.0
    for _ in range(60):
        _advance(frequencies, eta, rate, s, eta_s, rate_s)
        wi, vi = _to_physical(from_coupled, eta_s, rate_s, q, v)
        gap = wi
        for j in range(q.shape[0]):
            gap -= phi[j] * q[j]
        if gap < 0.0:
            break
        s += shift
        shift *= 2.0
    return s, wi, vi


@numba.njit(cache=True)
def _advance(frequencies, eta, rate, s, eta_out, rate_out):
    """Exact propagation of every coupled oscillator over s [s]."""
    for k in range(eta.shape[0]):
        x = frequencies[k] * s
        cx = math.cos(x)
        sx = math.sin(x)
        eta_out[k] = eta[k] * cx + rate[k] / frequencies[k] * sx
        rate_out[k] = rate[k] * cx - eta[k] * frequencies[k] * sx


@numba.njit(cache=True)
def _amplitudes(frequencies, force_row, eta, rate):
    """A_k [N]: the amplitude of each coupled mode's share of F for the state (η, η̇);
    constant through a contact (every coupled mode is an undamped oscillator)."""
    amplitude = np.empty(eta.shape[0])
    for k in range(eta.shape[0]):
        amplitude[k] = abs(force_row[k]) * math.sqrt(eta[k] ** 2 + (rate[k] / frequencies[k]) ** 2)
    return amplitude


@numba.njit(cache=True)
def _content_step(frequencies, force_row, eta, rate, resolution):
    """The contact step [s] for the state (η, η̇): :data:`SAMPLED_PHASE`/Ω of the coupled
    mode of largest amplitude, and at most 1/Ω of the fastest mode that must be sampled
    (the fastest modes whose amplitudes sum to at most ``resolution``/2 of the total are
    left unsampled; module docstring); 0 when the state carries no force at all."""
    amplitude = _amplitudes(frequencies, force_row, eta, rate)
    total = 0.0
    for k in range(eta.shape[0]):
        total += amplitude[k]
    if total == 0.0:
        return 0.0
    dominant = np.argmax(amplitude)
    tail = 0.0
    fastest = 0
    for k in range(eta.shape[0] - 1, -1, -1):
        tail += amplitude[k]
        if 2.0 * tail > resolution * total:
            fastest = k
            break
    return min(SAMPLED_PHASE / frequencies[dominant], 1.0 / frequencies[fastest])


@numba.njit(cache=True)
def _to_physical(from_coupled, eta, rate, q, v):
    """(w_i, v_i) and the modal state (q, v) of the coupled state (η, η̇)."""
    n = eta.shape[0]
    wi = 0.0
    vi = 0.0
    for k in range(n):
        wi += from_coupled[0, k] * eta[k]
        vi += from_coupled[0, k] * rate[k]
    for j in range(1, n):
        qj = 0.0
        vj = 0.0
        for k in range(n):
            qj += from_coupled[j, k] * eta[k]
            vj += from_coupled[j, k] * rate[k]
        q[j - 1] = qj
        v[j - 1] = vj
    return wi, vi


@numba.njit(cache=True)
def _record_inside(from_coupled, frequencies, force_row, eta, rate, t, length, spacing,
                   omega, phi, residual, q, v, history, rec):
    """Record exact rows inside a step of ``length`` [s] from time t [s] and state (η, η̇),
    at most ``spacing`` [s] apart (the step's end row is written by the caller); q and v
    serve as scratch. Returns the history and the next row."""
    count = int(math.ceil(length / spacing))
    if count <= 1:
        return history, rec
    n = eta.shape[0]
    eta_s = np.empty(n)
    rate_s = np.empty(n)
    for i in range(1, count):
        s = length * i / count
        _advance(frequencies, eta, rate, s, eta_s, rate_s)
        force = 0.0
        for k in range(n):
            force += force_row[k] * eta_s[k]
        wi, vi = _to_physical(from_coupled, eta_s, rate_s, q, v)
        history, rec = record_row(history, rec, t + s, max(force, 0.0), wi, vi, residual, omega, phi, q, v)
    return history, rec


@numba.njit(cache=True)
def _partial_force(force_row, eta, count):
    """Σ_{k<count} c_k η_k [N]: the force of the ``count`` slowest coupled modes."""
    total = 0.0
    for k in range(count):
        total += force_row[k] * eta[k]
    return total


@numba.njit(cache=True)
def _step(frequencies, eta, rate, cos_s, sin_s, eta_out, rate_out):
    """Exact propagation over the step whose cos Ω_k s, sin Ω_k s are given (the
    arithmetic of every stepping loop here, so that two loops reach one sample alike)."""
    for k in range(eta.shape[0]):
        eta_out[k] = eta[k] * cos_s[k] + rate[k] / frequencies[k] * sin_s[k]
        rate_out[k] = rate[k] * cos_s[k] - eta[k] * frequencies[k] * sin_s[k]


@numba.njit(cache=True)
def _coarse_plan(frequencies, force_row, eta, rate, h):
    """The coarse rate of a contact whose fine step is h [s].

    Returns ``(every, H, cos Ω_k H, sin Ω_k H, low, margin)``: H = every·h [s], the
    whole number of fine steps in the content step of :data:`COARSE_RESOLUTION` (so the
    coarse samples lie on the fine grid); the ``low`` slowest coupled modes have
    Ω_k H ≤ 1; ``margin`` [N] = Σ A_k of the others + H²/8 Σ_low A_k Ω_k² bounds how far
    F lies below (above) the smaller (larger) of the two samples of F_low = Σ_low c_k η_k
    anywhere in a coarse step (the ripple of the fast modes, and the chord error of the
    slow ones). ``every`` is 0 (a single rate) under :data:`COARSE_FACTOR`.
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


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def _record_step(modes, rows, start, end, t, length, force, history, rec, q, v):
    """Record a step of ``length`` [s] from time t [s]: exact rows inside, and its end
    (state ``end``, force [N]); q and v serve as scratch."""
    frequencies, force_row, from_coupled = modes
    row_spacing, omega, phi, residual = rows
    history, rec = _record_inside(from_coupled, frequencies, force_row, start[0], start[1], t, length,
                                  row_spacing, omega, phi, residual, q, v, history, rec)
    wi, vi = _to_physical(from_coupled, end[0], end[1], q, v)
    return record_row(history, rec, t + length, force, wi, vi, residual, omega, phi, q, v)


@numba.njit(cache=True)
def _fine_steps(modes, rows, fine, coarse, limits, state, run, record, history, rec, q, v):
    """Steps of the fine step h: the single-rate loop of the contact phase.

    ``state`` = (η, η̇, η_prev, η̇_prev) at time t and one step before; ``run`` = (t,
    F(t), F one step before (< 0: none), peak, peak time, steps). A sample where F ≤ 0
    ends the contact at the root of F in the step before it; a sampled maximum of F
    is refined to the root of the rate of the ``resolved`` coupled modes over the two
    steps around it, and evaluated with all modes. With ``coarse[0]`` = 0 the loop runs
    to the separation or the run's limits; otherwise it also stops (``stopped``) at the
    first sample after its start, its maximum test done, from which the coarse step is
    :func:`_skippable`.

    Returns (state, run, separated, stopped, wi, vi, history, rec).
    """
    frequencies, force_row, from_coupled = modes
    row_spacing, omega, phi, residual = rows
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
            s = _root(frequencies, force_row, eta, rate, start, h, False, n)
            # (η, η̇) at the separation land in eta_next, rate_next
            s, _wi, _vi = _clear_gap(from_coupled, frequencies, eta, rate, phi, s, h, eta_next, rate_next, q, v)
            if record:
                history, rec = _record_inside(from_coupled, frequencies, force_row, eta, rate, t, s,
                                              row_spacing, omega, phi, residual, q, v, history, rec)
            t += s
            force = 0.0
            separated = True
        else:
            if f_prev >= 0.0 and force >= f_prev and force >= f_next:
                # a sampled maximum: the peak is where the rate of the sampled coupled modes
                # vanishes over the two steps around it (the force there, ripple included)
                if (_force_rate(frequencies, force_row, eta_prev, rate_prev, 0.0, resolved) > 0.0
                        and _force_rate(frequencies, force_row, eta_prev, rate_prev, 2.0 * h, resolved) < 0.0):
                    s = _root(frequencies, force_row, eta_prev, rate_prev, 0.0, 2.0 * h, True, resolved)
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
                history, rec = _record_inside(from_coupled, frequencies, force_row, eta, rate, t, h,
                                              row_spacing, omega, phi, residual, q, v, history, rec)
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


@numba.njit(cache=True)
def _settle(modes, rows, coarse, anchor, scalars, peak, flush, record, history, rec, q, v):
    """Move the anchor (the first coarse sample not yet proven skippable, ``anchor`` =
    (η, η̇, scratch, scratch), ``scalars`` = (t, F, F_low, pending coarse steps after it))
    over the coarse steps that ``peak`` [N] now proves free of a larger force (all of
    them if ``flush``), recording them. Returns (scalars, history, rec)."""
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


@numba.njit(cache=True)
def _coarse_steps(modes, rows, coarse, limits, state, run, record, history, rec, q, v):
    """Coarse steps H from a sample where the fine loop stopped, to the start of the next
    fine window or the run's limits.

    A coarse step is taken (and recorded) outright when :func:`_skippable`; one whose
    F_low samples leave room for a force above the peak found so far is taken
    provisionally, from an anchor, until later
    samples raise the peak enough (:func:`_settle`). A fine window is due from the anchor
    (else from the current sample) when a step may hold F ≤ 0, or when a step is
    skippable while provisional steps remain before it. ``state`` = (η, η̇) and ``run`` =
    (t, F, peak, peak time, steps) at the start. Returns (η, η̇, run, done, wi, vi, history, rec): the window's start, or
    (``done``) the state at the run's limits.
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


@numba.njit(cache=True)
def contact_phase(frequencies, force_row, from_coupled, to_coupled, row_spacing, step_scale,
                  omega, phi, residual, t, wi, vi, q, v, peak, peak_time, steps, max_time, max_steps,
                  record, history, rec, two_rate=True):
    """One contact, from touchdown (α = 0) to separation or the run's limits.

    Parameters
    ----------
    frequencies, force_row, from_coupled, to_coupled : arrays of :class:`CoupledModes`.
    row_spacing : float
        Longest spacing of the recorded rows in contact [s] (the settings'
        ``time_step_ratio/ω``): a recorded run adds exact rows inside its steps, so its
        history is as fine as the sampled scheme's and its scalars are those of the run
        without a record.
    step_scale : float
        Factor on the step (the settings' ``step_scale``).
    omega, phi, residual : retained modes [rad/s], participations, residual [m/N].
    t, wi, vi, q, v : time [s] and state at touchdown; q and v are overwritten with the
        state at the end.
    peak, peak_time : largest force so far [N] and its time [s].
    steps, max_time, max_steps : steps taken so far, the run's time limit [s] and budget.
    record, history, rec : history array and next row (:mod:`history_rows`).
    two_rate : bool
        Take coarse steps where they are proven to change nothing (module docstring);
        ``False`` keeps the fine step throughout (the reference the tests compare with).

    Returns
    -------
    tuple
        (t, wi, vi, force, peak, peak_time, steps, separated, history, rec): the state
        at the end of the phase, with ``force`` 0 after a separation. A graze (no force
        anywhere in the first step) returns with ``steps`` unchanged, a round-off moment
        later, where the gap is strictly open.
    """
    n = frequencies.shape[0]
    eta = np.empty(n)
    rate = np.empty(n)
    for k in range(n):
        eta[k] = to_coupled[k, 0] * wi
        rate[k] = to_coupled[k, 0] * vi
        for j in range(1, n):
            eta[k] += to_coupled[k, j] * q[j - 1]
            rate[k] += to_coupled[k, j] * v[j - 1]
    h = step_scale * _content_step(frequencies, force_row, eta, rate, CONTACT_RESOLUTION)
    if h == 0.0 or _first_positive(frequencies, force_row, eta, rate, h) == 0.0:
        # grazing: no force anywhere in the first step (a touchdown at zero closing speed
        # whose force grows at second order — a sphere resting on a structure that
        # accelerates into it — is a contact: its force is positive just after touchdown);
        # leave with the gap strictly open, or flight would find this touchdown again
        if h == 0.0:
            h = 1e-9 / frequencies[n - 1]
        s, wi, vi = _clear_gap(from_coupled, frequencies, eta, rate, phi, 0.0, h, np.empty(n), np.empty(n), q, v)
        return t + s, wi, vi, 0.0, peak, peak_time, steps, True, history, rec
    resolved = 0  # coupled modes sampled at least 2π times per period (ascending Ω)
    while resolved < n and frequencies[resolved] * h <= 1.0:
        resolved += 1
    modes = (frequencies, force_row, from_coupled)
    rows = (row_spacing, omega, phi, residual)
    fine = (h, np.cos(frequencies * h), np.sin(frequencies * h), resolved)
    coarse = _coarse_plan(frequencies, force_row, eta, rate, h) if two_rate else \
        (0, 0.0, np.empty(0), np.empty(0), 0, 0.0)
    limits = (max_time, max_steps)
    state = (eta, rate, np.empty(n), np.empty(n))
    run = (t, 0.0, -1.0, peak, peak_time, steps)  # no force, and no sample before touchdown
    while True:
        state, run, separated, stopped, wi, vi, history, rec = _fine_steps(
            modes, rows, fine, coarse, limits, state, run, record, history, rec, q, v)
        t, force, f_prev, peak, peak_time, steps = run
        if not stopped:
            return t, wi, vi, force, peak, peak_time, steps, separated, history, rec
        eta, rate, (t, force, peak, peak_time, steps), done, wi, vi, history, rec = _coarse_steps(
            modes, rows, coarse, limits, (state[0], state[1]), (t, force, peak, peak_time, steps),
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
