r"""Sphere on an infinite Euler beam with linear contact (seed 001 eq 36, spec 3.5).

In normalised time ``τ = ωt`` (ω = sqrt(K/m_i)) and indentation ``ᾱ = α ω/V0`` the first
contact obeys the fractional oscillator

    ᾱ'' + 2ζ ∫0^τ ᾱ'(s)/sqrt(τ − s) ds + ᾱ = 0,    ᾱ(0) = 0,  ᾱ'(0) = 1,

with ζ the beam loss factor as *corrected* in spec section 1 (``ζ_b``, half the value of
seed 001's printed eq 38). With ``c = sqrt(π) ζ`` the Laplace transform is
``A(s) = 1/(s² + 2c s^{1/2} + 1)``. Three independent evaluations are provided:

``"closed-form"``
    With ``q_j`` the four roots of ``P(q) = q⁴ + 2cq + 1``, partial fractions in
    ``p = s^{1/2}`` and ``L⁻¹[1/(s^{1/2} − q)] = 1/sqrt(πτ) + q e^{q²τ} erfc(−q sqrt τ)`` give

        ᾱ(τ) = Re Σ_j q_j/P'(q_j) · e^{q_j²τ} erfc(−q_j sqrt τ)

    (the ``1/sqrt(πτ)`` terms cancel because ``Σ 1/P'(q_j) = 0``). Each factor is the
    Faddeeva function, ``e^{u²} erfc(−u) = w(−iu)``. For the two roots with ``Re q < 0``
    (not on the principal sheet of ``s^{1/2}``) ``Im(−iu) > 0`` and ``w`` is bounded; for the
    two with ``Re q > 0`` (the true poles ``s = q²`` of ``A``, always a damped complex pair)
    the equivalent ``2 e^{q²τ} − w(iu)`` is used, again with ``w`` in the upper half-plane,
    so nothing overflows for any τ. The same sums with ``q_j^k`` give ``ᾱ' (k = 3)`` and the
    impactor velocity ``1 − ∫ᾱ = −Re Σ q_j^{-1}/P'(q_j) w(…)`` (``k = −1``). The two roots with
    ``Re q < 0`` collide at ``c = 2·3^{-3/4}`` (ζ ≈ 0.495010); near there their pair of terms
    is summed as a contour integral of ``q^k w(−iq sqrt τ)/P(q)`` around both (trapezoidal
    rule on a circle), which has no cancellation.
``"talbot"``
    Fixed-Talbot inversion (Abate & Valkó, Int. J. Numer. Meth. Eng. 60, 2004, 979–993)
    of ``A(s)`` minus its two pole terms, the poles' residues being added back in closed
    form. Without the subtraction the Talbot contour misses the poles at large τ (it
    shrinks like 1/τ) and the inversion is wrong there.
``"cq"``
    Lubich's convolution quadrature (BDF2) of the receptance form
    ``ᾱ(τ) = τ − ∫0^τ G(τ − s) F̄(s) ds``, ``G(τ) = τ + 4ζ sqrt τ``
    (Laplace ``s^{-2} + 2c s^{-3/2}``), second order in the step. The same stepper with
    ``F̄ = max(ᾱ, 0)`` follows separation and re-impact (:func:`infinite_beam_impact`);
    both live in :mod:`impactmaps.closed_forms.infinite_beam_cq`.

Findings (see the module tests):

* ᾱ stays positive for all τ when ζ ≥ ζ_crit = 1.01288831287 (:func:`critical_beam_loss_factor`):
  the first local minimum of ᾱ touches zero there; later minima are higher and
  ``ᾱ ~ ζ τ^{-3/2} > 0`` as τ → ∞ (branch point of ``s^{1/2}``), the pole part decaying
  exponentially.
* Re-impact *does* happen on an infinite beam. After separation the beam point keeps
  moving away with velocity ``2ζ ∫ F̄(s)/sqrt(τ − s) ds > 0`` that decays like τ^{-1/2}, while
  the impactor flies at the constant velocity it had at separation. If that velocity is
  ≤ 0 (rebound) the gap only grows; if it is > 0 the impactor catches up with the beam,
  whose displacement grows only like sqrt τ, and strikes again. The impactor still moves
  forward at separation for ζ_r = 0.261046261 < ζ < ζ_crit
  (:func:`recontact_beam_loss_factor`), so :func:`infinite_beam_force` continues with the
  convolution-quadrature stepper there. The later contacts are weak (F̄ ≲ 0.06 against a
  first peak ≥ 0.33); in every run so far the impactor ended up riding on the beam, the
  last contact lasting to the end of the run.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import wofz

from .._checks import require_choice, require_nonnegative, require_positive
from .infinite_beam_cq import (
    DEFAULT_TIME_STEP,
    InfiniteBeamImpact,
    cq_grid,
    cq_march,
    infinite_beam_impact,
)

__all__ = [
    "INFINITE_BEAM_METHODS",
    "InfiniteBeamImpact",
    "critical_beam_loss_factor",
    "infinite_beam_contact_time",
    "infinite_beam_force",
    "infinite_beam_impact",
    "infinite_beam_impactor_velocity",
    "infinite_beam_indentation",
    "infinite_beam_indentation_rate",
    "infinite_beam_peak",
    "infinite_beam_peak_time",
    "recontact_beam_loss_factor",
]

INFINITE_BEAM_METHODS = ("closed-form", "talbot", "cq")
TALBOT_NODES = 24  # balances truncation 10^{-0.6M} against round-off e^{0.4M}·eps
_PAIR_MERGE_DISTANCE = 0.05  # roots with Re q < 0 closer than this: contour sum
_PAIR_CONTOUR_RADIUS = 0.25
_PAIR_CONTOUR_NODES = 32


# --------------------------------------------------------------------------- roots


@functools.lru_cache(maxsize=256)
def _roots(loss_factor: float):
    """Roots of P(q) = q⁴ + 2cq + 1: (principal pair, Re q > 0; other pair; c).

    Simple roots are polished by Newton's method. The other pair may be (nearly) double
    (at c = 2·3^{-3/4}); it is then left as computed and summed by a contour integral.
    """
    c = math.sqrt(math.pi) * loss_factor
    roots = np.roots([1.0, 0.0, 0.0, 2.0 * c, 1.0]).astype(complex)
    principal = roots[roots.real > 0]
    other = roots[roots.real <= 0]
    if principal.size != 2:  # impossible: P has no roots on the imaginary axis
        raise RuntimeError(f"unexpected root configuration for loss_factor={loss_factor}: {roots}")
    principal = _newton(principal, c)
    if not _close_pair(other):
        other = _newton(other, c)
    principal.setflags(write=False)  # cached: callers share these arrays
    other.setflags(write=False)
    return principal, other, c


def _newton(roots, c, iterations=3):
    for _ in range(iterations):
        roots = roots - _quartic(roots, c) / (4.0 * roots**3 + 2.0 * c)
    return roots


def _quartic(q, c):
    return q**4 + 2.0 * c * q + 1.0


def _close_pair(pair) -> bool:
    return abs(pair[0] - pair[1]) < _PAIR_MERGE_DISTANCE


def _moment(tau, loss_factor: float, power: int) -> np.ndarray:
    """Σ_j q_j^power/P'(q_j) · e^{q_j²τ} erfc(−q_j sqrt τ) (complex; real in exact arithmetic)."""
    principal, other, c = _roots(float(loss_factor))
    root_tau = np.sqrt(np.asarray(tau, dtype=float))
    total = np.zeros(root_tau.shape, dtype=complex)
    for q in principal:  # e^{u²}erfc(−u) = 2e^{u²} − w(iu), u = q√τ, Re u ≥ 0
        term = 2.0 * np.exp(q * q * root_tau**2) - wofz(1j * q * root_tau)
        total += q**power / (4.0 * q**3 + 2.0 * c) * term
    if _close_pair(other):
        # (1/2πi)∮ q^k w(−iq√τ)/P(q) dq around the close pair only (trapezoidal rule)
        centre = 0.5 * (other[0] + other[1])
        angles = 2j * np.pi * np.arange(_PAIR_CONTOUR_NODES) / _PAIR_CONTOUR_NODES
        ring = _PAIR_CONTOUR_RADIUS * np.exp(angles)
        nodes = centre + ring
        values = nodes**power * wofz(-1j * nodes * root_tau[..., None]) / _quartic(nodes, c)
        total += np.mean(values * ring, axis=-1)
    else:
        for q in other:  # e^{u²}erfc(−u) = w(−iu), Im(−iu) = −Re u ≥ 0
            total += q**power / (4.0 * q**3 + 2.0 * c) * wofz(-1j * q * root_tau)
    return total


# --------------------------------------------------------------------------- Talbot


def _fixed_talbot(transform, tau: np.ndarray, nodes: int = TALBOT_NODES) -> np.ndarray:
    """Fixed-Talbot inverse Laplace transform at τ > 0 (Abate & Valkó 2004, eq. 39).

    ``transform`` maps complex s (array) to F(s); it must be analytic off the negative real
    axis and satisfy F(conj s) = conj F(s).
    """
    tau = np.asarray(tau, dtype=float)[..., None]
    radius = 2.0 * nodes / (5.0 * tau)
    theta = np.pi * np.arange(1, nodes) / nodes
    cot = 1.0 / np.tan(theta)
    s = radius * theta * (cot + 1j)
    sigma = theta + (theta * cot - 1.0) * cot
    with np.errstate(under="ignore"):
        body = np.real(np.exp(tau * s) * transform(s) * (1.0 + 1j * sigma))
        start = 0.5 * np.real(transform(radius + 0j)) * np.exp(radius * tau)
    return (radius / nodes * (start + body.sum(axis=-1, keepdims=True)))[..., 0]


def _talbot_indentation(tau: np.ndarray, loss_factor: float) -> np.ndarray:
    principal, _, c = _roots(float(loss_factor))
    poles = principal**2  # s = q², q = s^{1/2} on the principal branch
    residues = 1.0 / (2.0 * poles + c / principal)  # 1/D'(s), D = s² + 2c s^{1/2} + 1

    def remainder(s):
        value = 1.0 / (s * s + 2.0 * c * np.sqrt(s) + 1.0)
        for pole, residue in zip(poles, residues):
            value = value - residue / (s - pole)
        return value

    tau = np.asarray(tau, dtype=float)
    result = np.zeros(tau.shape)
    positive = tau > 0
    pole_part = sum(r * np.exp(pole * tau[positive]) for pole, r in zip(poles, residues))
    result[positive] = np.real(pole_part) + _fixed_talbot(remainder, tau[positive])
    return result


# --------------------------------------------------------------------------- public API


def scalar_or_array(value: np.ndarray):
    """0-d arrays become numpy scalars, anything else is returned as is."""
    return value[()] if value.ndim == 0 else value


def _validated(tau, loss_factor):
    require_nonnegative("tau", tau)
    require_positive("loss_factor", loss_factor)
    return np.broadcast_arrays(np.asarray(tau, dtype=float), np.asarray(loss_factor, dtype=float))


def _per_loss_factor(tau, loss_factor, evaluate):
    """Apply ``evaluate(tau_array, zeta_scalar)`` over the distinct loss factors."""
    tau, loss_factor = _validated(tau, loss_factor)
    result = np.empty(tau.shape)
    for zeta in np.unique(loss_factor):
        chosen = loss_factor == zeta
        result[chosen] = evaluate(tau[chosen], float(zeta))
    return scalar_or_array(result)


def infinite_beam_indentation(
    tau, loss_factor, method="closed-form", *, time_step=DEFAULT_TIME_STEP
):
    """Normalised indentation ᾱ(τ) of the linear infinite-beam problem (eq 36).

    This is the solution of the *linear* equation (no separation): it equals the
    contact force up to the first zero (see :func:`infinite_beam_force`).

    Parameters
    ----------
    tau : array_like
        Normalised time τ = ω t [-], ≥ 0.
    loss_factor : array_like
        Beam loss factor ζ_b [-] (spec section 1), > 0; broadcast against ``tau``.
    method : {"closed-form", "talbot", "cq"}
        Closed form with the Faddeeva function (default, accurate to ~1e-15); fixed-Talbot
        inversion with pole subtraction (~1e-11); BDF2 convolution quadrature on a uniform
        grid with step ``time_step`` and cubic interpolation (error O(step²)).
    time_step : float, optional
        Normalised step for ``method="cq"`` [-].

    Returns
    -------
    ndarray
        ᾱ = α ω/V0 [-], the shape of the broadcast inputs.
    """
    require_choice("method", method, INFINITE_BEAM_METHODS)
    require_positive("time_step", time_step)
    if method == "closed-form":
        return _per_loss_factor(tau, loss_factor, lambda t, z: _moment(t, z, 1).real)
    if method == "talbot":
        return _per_loss_factor(tau, loss_factor, _talbot_indentation)

    def by_cq(t, zeta):
        step, count = cq_grid(max(float(t.max()), 2 * time_step), float(time_step))
        grid, _, indentation = cq_march(zeta, step, count, False)
        from scipy.interpolate import CubicSpline  # ~0.3 s to import: only where a curve is resampled

        return CubicSpline(grid, indentation)(t)

    return _per_loss_factor(tau, loss_factor, by_cq)


def infinite_beam_indentation_rate(tau, loss_factor):
    """Normalised indentation rate ᾱ'(τ) = Re Σ q_j³/P'(q_j) w(−i q_j sqrt τ) (closed form).

    Parameters
    ----------
    tau : array_like
        Normalised time τ [-], ≥ 0.
    loss_factor : array_like
        Beam loss factor ζ_b [-], > 0.

    Returns
    -------
    ndarray
        dᾱ/dτ = α̇/V0 [-] of the linear solution.
    """
    return _per_loss_factor(tau, loss_factor, lambda t, z: _moment(t, z, 3).real)


def infinite_beam_impactor_velocity(tau, loss_factor):
    """Impactor velocity of the linear solution, 1 − ∫0^τ ᾱ = −Re Σ q_j^{-1}/P'(q_j) w(…).

    Parameters
    ----------
    tau : array_like
        Normalised time τ [-], ≥ 0.
    loss_factor : array_like
        Beam loss factor ζ_b [-], > 0.

    Returns
    -------
    ndarray
        ẇ_i/V0 [-]; the beam-point velocity is this minus ᾱ'.
    """
    return _per_loss_factor(tau, loss_factor, lambda t, z: -_moment(t, z, -1).real)


def _brentq(*args, **options):
    """:func:`scipy.optimize.brentq`, imported on first use (scipy.optimize takes ~0.3 s to
    import; a map lookup imports this module but finds no root)."""
    from scipy.optimize import brentq

    return brentq(*args, **options)


@functools.lru_cache(maxsize=1024)
def _first_contact(loss_factor: float):
    """(peak time, peak, time of first local minimum or nan, value there, contact time)."""
    rate = lambda t: _moment(t, loss_factor, 3).real  # noqa: E731
    value = lambda t: _moment(t, loss_factor, 1).real  # noqa: E731
    # time scale of the response: 1 (contact) or |s_pole|^{-1} ≈ (2c)^{-2/3} for large ζ;
    # peak and first trough lie within 6 scales (small ζ: π/2 and 3π/2)
    scale = min(1.0, (2.0 * math.sqrt(math.pi) * loss_factor) ** (-2.0 / 3.0))
    grid = scale * np.unique(np.r_[np.geomspace(1e-3, 1.0, 200), np.linspace(1.0, 15.0, 2800)])
    changes = np.flatnonzero(np.diff(np.sign(rate(grid))) != 0)
    peak_time = _brentq(rate, grid[changes[0]], grid[changes[0] + 1], xtol=1e-15, rtol=1e-15)
    if changes.size < 2:
        return peak_time, float(value(peak_time)), math.nan, math.nan, math.inf
    low, high = grid[changes[1]], grid[changes[1] + 1]
    trough_time = _brentq(rate, low, high, xtol=1e-15, rtol=1e-15)
    trough = float(value(trough_time))
    contact = math.inf
    if trough < 0:
        contact = _brentq(value, peak_time, trough_time, xtol=1e-15, rtol=1e-15)
    return peak_time, float(value(peak_time)), trough_time, trough, contact


def _over_loss_factors(loss_factor, index):
    require_positive("loss_factor", loss_factor)
    zeta = np.asarray(loss_factor, dtype=float)
    result = np.vectorize(lambda z: _first_contact(float(z))[index], otypes=[float])(zeta)
    return scalar_or_array(result)


def infinite_beam_peak(loss_factor):
    """Peak normalised force F̄max of the infinite beam (first local maximum of ᾱ).

    Found as the first zero of the closed-form ᾱ' by Brent's method (accurate to ~1e-14;
    later re-impacts are far weaker, F̄ ≲ 0.06).

    Parameters
    ----------
    loss_factor : array_like
        Beam loss factor ζ_b [-], > 0.

    Returns
    -------
    float or ndarray
        F̄max = F_max/(m_i V0 ω) [-].
    """
    return _over_loss_factors(loss_factor, 1)


def infinite_beam_peak_time(loss_factor):
    """Normalised time of the peak force, τ_max = ω t_max [-] (see :func:`infinite_beam_peak`)."""
    return _over_loss_factors(loss_factor, 0)


def infinite_beam_contact_time(loss_factor):
    """Normalised duration of the first contact, the first zero of ᾱ [-].

    ``inf`` for ζ ≥ :func:`critical_beam_loss_factor` (ᾱ > 0 for all τ: the impactor never
    separates from an infinite beam; on a finite beam reflections end the contact). For
    :func:`recontact_beam_loss_factor` < ζ < ζ_crit further contacts follow, see
    :func:`infinite_beam_impact`.

    Parameters
    ----------
    loss_factor : array_like
        Beam loss factor ζ_b [-], > 0.

    Returns
    -------
    float or ndarray
        τ_c = ω t_c [-].
    """
    return _over_loss_factors(loss_factor, 4)


@functools.lru_cache(maxsize=1)
def critical_beam_loss_factor() -> float:
    """Loss factor ζ_crit ≈ 1.01288831287 above which ᾱ(τ) > 0 for all τ > 0.

    At ζ_crit the first local minimum of ᾱ (second zero of ᾱ') touches zero: solved by
    Brent's method on ζ ↦ ᾱ(τ_min(ζ)), which increases through zero there. Later minima
    are higher (checked to τ = 1e4 in the tests) and ``ᾱ ~ ζτ^{-3/2}`` as τ → ∞.
    Cross-checked independently by solving ᾱ = ᾱ' = 0 with mpmath's 30-digit de Hoog
    inversion: ζ_crit = 1.0128883128721652, τ = 2.1130419971738.

    Returns
    -------
    float
        ζ_crit [-] (spec's corrected beam loss factor; the paper's printed eq 38 gives 2ζ).
    """
    return _brentq(lambda z: _first_contact(z)[3], 0.9, 1.1, xtol=1e-15, rtol=1e-15)


@functools.lru_cache(maxsize=1)
def recontact_beam_loss_factor() -> float:
    """Loss factor ζ_r ≈ 0.261046261 above which the impactor, at the first separation, still
    moves towards the infinite beam, so that it strikes again (up to ζ_crit).

    Root of ζ ↦ 1 − ∫0^{τ_c} ᾱ dτ (impactor velocity at separation) by Brent's method.
    Cross-checked by solving ᾱ(τ) = 0, ∫0^τ ᾱ = 1 with mpmath's 30-digit de Hoog inversion:
    ζ_r = 0.26104626106154511, τ_c = 2.5522467471360416.

    Returns
    -------
    float
        ζ_r [-].
    """
    return _brentq(_separation_velocity, 0.2, 0.3, xtol=1e-15, rtol=1e-15)


def _separation_velocity(loss_factor: float) -> float:
    contact = _first_contact(float(loss_factor))[4]
    if math.isinf(contact):
        return 0.0
    return float(-_moment(contact, float(loss_factor), -1).real)


def infinite_beam_force(tau, loss_factor, *, time_step=DEFAULT_TIME_STEP):
    """Normalised contact force F̄(τ) of a sphere on an infinite beam, with re-impacts.

    Exact (closed form) up to the first separation. After it the force is zero if the
    impactor then moves away (ζ ≤ :func:`recontact_beam_loss_factor`: proved, the gap grows
    monotonically); otherwise the impactor strikes again and the history is continued by
    the unilateral convolution-quadrature stepper started from the exact first contact
    (error O(step²) in the later contacts, whose forces are ≲ 0.06).

    Parameters
    ----------
    tau : array_like
        Normalised time τ = ω t [-], ≥ 0.
    loss_factor : float
        Beam loss factor ζ_b [-], > 0 (scalar).
    time_step : float, optional
        Normalised step of the stepper for re-impacts [-].

    Returns
    -------
    ndarray
        F̄ = F/(m_i V0 ω) [-], shape of ``tau``.
    """
    require_positive("loss_factor", loss_factor)
    if np.ndim(loss_factor) != 0:
        raise ValueError(f"loss_factor = {loss_factor!r} is invalid: must be a scalar > 0")
    require_positive("time_step", time_step)
    require_nonnegative("tau", tau)
    zeta = float(loss_factor)
    tau = np.asarray(tau, dtype=float)
    contact = _first_contact(zeta)[4]
    force = np.where(tau <= contact, np.maximum(_moment(tau, zeta, 1).real, 0.0), 0.0)
    later = tau > contact
    if np.any(later) and _separation_velocity(zeta) > 0:
        run = infinite_beam_impact(
            zeta,
            float(tau.max()),
            time_step=time_step,
            prescribed_force=lambda t: np.where(t <= contact, _moment(t, zeta, 1).real, -1.0),
        )
        force[later] = np.interp(tau[later], run.tau, run.force)
    return scalar_or_array(force)
