"""Sphere on an infinite Euler beam with linear contact (seed 001 eq 36, spec 3.5).

The normalised indentation, its rate, the impactor velocity, the peak, the contact time
and the force with re-impacts of ``ᾱ'' + 2ζ ∫0^τ ᾱ'(s)/sqrt(τ − s) ds + ᾱ = 0``, by a
closed form (Faddeeva), fixed-Talbot inversion or convolution quadrature. Derivation and
the critical loss factors: docs/physics.rst (Closed forms).
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
    """Roots of P(q) = q⁴ + 2cq + 1: (principal pair, Re q > 0; other pair; c)."""
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
    """Fixed-Talbot inverse Laplace transform of ``transform`` at τ > 0 (Abate & Valkó 2004, eq. 39)."""
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
    """Normalised indentation ᾱ(τ) of the linear infinite-beam problem (no separation).

    Parameters
    ----------
    tau : array_like
        Normalised time τ = ω t [-], ≥ 0.
    loss_factor : array_like
        Beam loss factor ζ_b [-], > 0; broadcast against ``tau``.
    method : {"closed-form", "talbot", "cq"}
        Closed form (default, ~1e-15), fixed-Talbot (~1e-11) or BDF2 convolution
        quadrature (O(step²)).
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
    """Normalised indentation rate ᾱ'(τ) = α̇/V0 [-] at τ ≥ 0 for ζ_b > 0 (closed form)."""
    return _per_loss_factor(tau, loss_factor, lambda t, z: _moment(t, z, 3).real)


def infinite_beam_impactor_velocity(tau, loss_factor):
    """Impactor velocity over V0, ``1 − ∫0^τ ᾱ`` [-], of the linear solution at τ ≥ 0 for ζ_b > 0."""
    return _per_loss_factor(tau, loss_factor, lambda t, z: -_moment(t, z, -1).real)


def _brentq(*args, **options):
    """``scipy.optimize.brentq``, imported on first use."""
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
    """Peak normalised force F̄max = F_max/(m_i V0 ω) [-] of the infinite beam at ζ_b > 0 [-]."""
    return _over_loss_factors(loss_factor, 1)


def infinite_beam_peak_time(loss_factor):
    """Normalised time of the peak force, τ_max = ω t_max [-] (see :func:`infinite_beam_peak`)."""
    return _over_loss_factors(loss_factor, 0)


def infinite_beam_contact_time(loss_factor):
    """Normalised duration τ_c = ω t_c [-] of the first contact at ζ_b > 0 (``inf`` for ζ ≥ ζ_crit)."""
    return _over_loss_factors(loss_factor, 4)


@functools.lru_cache(maxsize=1)
def critical_beam_loss_factor() -> float:
    """Loss factor ζ_crit ≈ 1.01288831287 [-] above which ᾱ(τ) > 0 for all τ > 0."""
    return _brentq(lambda z: _first_contact(z)[3], 0.9, 1.1, xtol=1e-15, rtol=1e-15)


@functools.lru_cache(maxsize=1)
def recontact_beam_loss_factor() -> float:
    """Loss factor ζ_r ≈ 0.261046261 [-] above which the impactor strikes the infinite beam again (up to ζ_crit)."""
    return _brentq(_separation_velocity, 0.2, 0.3, xtol=1e-15, rtol=1e-15)


def _separation_velocity(loss_factor: float) -> float:
    contact = _first_contact(float(loss_factor))[4]
    if math.isinf(contact):
        return 0.0
    return float(-_moment(contact, float(loss_factor), -1).real)


def infinite_beam_force(tau, loss_factor, *, time_step=DEFAULT_TIME_STEP):
    """Normalised contact force F̄ = F/(m_i V0 ω) [-] on an infinite beam, with re-impacts.

    Exact up to the first separation; later contacts (ζ_r < ζ < ζ_crit) by the
    convolution-quadrature stepper (O(step²)).

    Parameters
    ----------
    tau : array_like
        Normalised time τ = ω t [-], ≥ 0.
    loss_factor : float
        Beam loss factor ζ_b [-], > 0 (scalar).
    time_step : float, optional
        Normalised step of the stepper for re-impacts [-].
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
