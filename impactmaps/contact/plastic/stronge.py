"""The refined Stronge elastic-plastic sphere contact law (seed 000), made energy-consistent.

Hertz to first yield, a logarithmic mean-pressure rise over a consistent area law to the
fully plastic regime, Hertz unloading with the deformed radius. Equations, the change
from the printed form and the sources of the defaults: docs/contact_laws.rst.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from ..._checks import require_in_range, require_positive
from ..base import ContactLaw, law_option, register_contact_law
from .first_yield import (
    first_yield_force,
    first_yield_indentation,
    reference_impact_number,
    ReferenceYieldScales,
)

__all__ = ["StrongeContact", "stronge_area_law", "stronge_continuity_coefficient"]

#: Default ``c_y``: Hertz peak pressure at first yield ``p0 = 1.60 Y`` (Johnson 1985, §6.2).
DEFAULT_YIELD_PRESSURE_FACTOR = 1.6
#: Default ``c_p``: fully plastic mean pressure ``p_m ≈ 2.8 Y`` (Tabor; Johnson 1985, §6.3).
DEFAULT_PLASTIC_PRESSURE_FACTOR = 2.8
#: Default ``δ_p/δ_y`` of the refined Stronge model (docs/physics_contract.md §2; not verified in print).
DEFAULT_PLASTIC_INDENTATION_RATIO = 84.0

_CHECK_POINTS = 4001  # grid of the elastic-plastic branch on which the constructor checks the contract
_CHECK_TOLERANCE = 1e-12  # relative slack of those checks (rounding of the equalities at δ_y)


def stronge_continuity_coefficient(
    yield_pressure_factor=DEFAULT_YIELD_PRESSURE_FACTOR,
    plastic_pressure_factor=DEFAULT_PLASTIC_PRESSURE_FACTOR,
    plastic_indentation_ratio=DEFAULT_PLASTIC_INDENTATION_RATIO,
):
    """``κ = ln(2δ_p/δ_y − 1) / (3c_p/(2c_y) − 1)`` [-]: force continuous at ``δ_p``."""
    c_y = np.asarray(yield_pressure_factor, float)
    c_p = np.asarray(plastic_pressure_factor, float)
    ratio = np.asarray(plastic_indentation_ratio, float)
    return np.log(2.0 * ratio - 1.0) / (1.5 * c_p / c_y - 1.0)


@functools.lru_cache(maxsize=256)
def _area_law(yield_pressure_factor: float, plastic_pressure_factor: float, plastic_indentation_ratio: float):
    """(κ, n, τ) of one set of constants, or ``None`` if no area law keeps the contract."""
    k = 1.5 * plastic_pressure_factor / yield_pressure_factor
    xp = plastic_indentation_ratio
    area_p = 2.0 * xp - 1.0
    kappa = math.log(area_p) / (k - 1.0)
    slope = 1.5 * kappa / (1.0 + kappa)
    target = math.log(area_p) / slope
    if not target < xp - 1.0:
        return None
    low, high = math.log(1e-12), math.log(1e12)
    for _ in range(200):
        mid = 0.5 * (low + high)
        tau = math.exp(mid)
        if tau * math.log1p((xp - 1.0) / tau) < target:
            low = mid
        else:
            high = mid
    tau = math.exp(0.5 * (low + high))
    exponent = slope * tau
    # the fully plastic line k(2x − 1) stays below Hertz x^{3/2} for every x ≥ x_p iff it
    # is below at x_p and x_p is past the minimum of their difference, x = 16k²/9
    if xp**1.5 < k * area_p or xp < 16.0 * k * k / 9.0:
        return None
    x = 1.0 + (xp - 1.0) * np.linspace(0.0, 1.0, _CHECK_POINTS) ** 2
    u = (x - 1.0 + tau) / tau
    area = u**exponent
    force = area * (1.0 + np.log(area) / kappa)
    tangent = exponent * u ** (exponent - 1.0) / tau * (1.0 + (1.0 + np.log(area)) / kappa)
    recovery = force / np.sqrt(area)
    slack = 1.0 + _CHECK_TOLERANCE
    keeps = (np.all(force <= x**1.5 * slack)  # loading ≤ Hertz
             and np.all(tangent <= 1.5 * np.sqrt(area) * slack)  # never stiffer than unloading
             and np.all(recovery <= x * slack)  # δ_r ≥ 0
             and np.all(np.diff(x - recovery) >= -_CHECK_TOLERANCE * x[1:]))  # δ_r non-decreasing
    return (kappa, exponent, tau) if keeps else None


def _smallest_valid_ratio(yield_pressure_factor: float, plastic_pressure_factor: float) -> float:
    """Smallest δ_p/δ_y whose law keeps the contract (bisection; validity is monotone in it)."""
    low, high = 1.0, 2.0
    while _area_law(yield_pressure_factor, plastic_pressure_factor, high) is None:
        low, high = high, 2.0 * high
        if high > 1e12:
            return math.inf
    for _ in range(40):
        mid = math.sqrt(low * high)
        if _area_law(yield_pressure_factor, plastic_pressure_factor, mid) is None:
            low = mid
        else:
            high = mid
    return high


def stronge_area_law(
    yield_pressure_factor=DEFAULT_YIELD_PRESSURE_FACTOR,
    plastic_pressure_factor=DEFAULT_PLASTIC_PRESSURE_FACTOR,
    plastic_indentation_ratio=DEFAULT_PLASTIC_INDENTATION_RATIO,
):
    """Exponent n and offset τ [-] of the area law ``A = ((x − 1 + τ)/τ)^n`` for ``c_y``, ``c_p``, ``δ_p/δ_y`` [-].

    Raises
    ------
    ValueError
        No such law keeps the contract (names ``plastic_indentation_ratio`` and its
        smallest valid value).
    """
    c_y, c_p, ratio = np.broadcast_arrays(np.asarray(yield_pressure_factor, float),
                                          np.asarray(plastic_pressure_factor, float),
                                          np.asarray(plastic_indentation_ratio, float))
    exponent = np.empty(c_y.shape)
    offset = np.empty(c_y.shape)
    for index in np.ndindex(c_y.shape):
        constants = (float(c_y[index]), float(c_p[index]), float(ratio[index]))
        law = _area_law(*constants)
        if law is None:
            smallest = _smallest_valid_ratio(*constants[:2])
            raise ValueError(
                f"plastic_indentation_ratio = {constants[2]!r} is invalid with yield_pressure_factor = "
                f"{constants[0]!r} and plastic_pressure_factor = {constants[1]!r}: the law would rise above "
                f"the elastic Hertz curve or return more work than it absorbs; valid range is "
                f"[{smallest:.6g}, inf)")
        exponent[index], offset[index] = law[1], law[2]
    return exponent, offset


@numba.njit(cache=True)
def _stronge_loading(delta, params):
    """(force, stiffness, contact radius) on the virgin loading curve, δ > 0."""
    modulus = params[0]
    radius = params[1]
    yield_delta = params[2]
    yield_force = params[3]
    plastic_delta = params[4]
    kappa = params[5]
    plastic_pressure = params[6]
    exponent = params[7]
    offset = params[8]
    if delta <= yield_delta:
        root = math.sqrt(delta)
        factor = modulus * math.sqrt(radius)
        return 4.0 / 3.0 * factor * delta * root, 2.0 * factor * root, math.sqrt(radius * delta)
    if delta <= plastic_delta:
        u = (delta / yield_delta - 1.0 + offset) / offset
        log_area = exponent * math.log(u)
        area = math.exp(log_area)
        force = yield_force * area * (1.0 + log_area / kappa)
        slope = exponent * area / (u * offset)  # dA/dx
        stiffness = yield_force / yield_delta * slope * (1.0 + (1.0 + log_area) / kappa)
        return force, stiffness, math.sqrt(radius * yield_delta * area)
    contact_radius = math.sqrt(radius * (2.0 * delta - yield_delta))
    return (
        math.pi * contact_radius * contact_radius * plastic_pressure,
        2.0 * math.pi * radius * plastic_pressure,
        contact_radius,
    )


@numba.njit(cache=True)
def _stronge_kernel(alpha, alpha_max, params):
    if alpha <= 0.0:
        return 0.0, 0.0
    if alpha >= alpha_max or alpha_max <= params[2]:  # loading, or never yielded
        force, stiffness, _a = _stronge_loading(alpha, params)
        return force, stiffness
    peak_force, _k, peak_radius = _stronge_loading(alpha_max, params)
    recovery = min(3.0 * peak_force / (4.0 * params[0] * peak_radius), alpha_max)  # δ_m − δ_r
    return hertz_unloading(alpha, alpha_max, peak_force, recovery)


@numba.njit(cache=True)
def hertz_unloading(alpha, alpha_max, peak_force, recovery):
    """(force [N], stiffness [N/m]) at δ = ``alpha`` on the Hertzian unloading curve from the peak
    (δ_m = ``alpha_max``, F_m = ``peak_force``) that recovers ``recovery`` = δ_m − δ_r [m]; zero below δ_r."""
    gap = alpha - (alpha_max - recovery)
    if gap <= 0.0:
        return 0.0, 0.0
    scale = peak_force / (recovery * math.sqrt(recovery))
    root = math.sqrt(gap)
    return scale * gap * root, 1.5 * scale * root


@register_contact_law
@dataclass(frozen=True)
class StrongeContact(ReferenceYieldScales, ContactLaw):
    """Refined Stronge elastic-plastic sphere–flat contact, energy-consistent (seed 000).

    Parameters
    ----------
    effective_modulus : float or array_like
        E* [Pa] (seed 001 eq 8).
    radius : float or array_like
        Sphere (effective) radius R [m].
    yield_strength : float or array_like
        Yield stress Y of the softer material [Pa].
    yield_pressure_factor : float or array_like, default 1.6
        ``c_y``: Hertz peak pressure at first yield is ``c_y Y`` [-].
    plastic_pressure_factor : float or array_like, default 2.8
        ``c_p``: fully plastic mean contact pressure is ``c_p Y`` [-]; > ``2c_y/3``.
    plastic_indentation_ratio : float or array_like, default 84
        ``δ_p/δ_y`` [-], onset of the fully plastic regime (≥ 37.39 with the default factors).

    Raises
    ------
    ValueError
        Constants for which the law would break the contact-law contract.
    """

    effective_modulus: float
    radius: float
    yield_strength: float
    yield_pressure_factor: float = law_option(
        DEFAULT_YIELD_PRESSURE_FACTOR, "", "c_y: the Hertz peak pressure at first yield is c_y Y")
    plastic_pressure_factor: float = law_option(
        DEFAULT_PLASTIC_PRESSURE_FACTOR, "", "c_p: the fully plastic mean contact pressure is c_p Y (> 2 c_y/3)")
    plastic_indentation_ratio: float = law_option(
        DEFAULT_PLASTIC_INDENTATION_RATIO, "",
        "δ_p/δ_y: onset of the fully plastic regime (large enough that the law stays below Hertz)")

    name: ClassVar[str] = "stronge"
    #: 2: the energy-consistent elastic-plastic area law (1 was the printed form).
    revision: ClassVar[int] = 2
    elastic: ClassVar[bool] = False
    needs_yield_strength: ClassVar[bool] = True
    kernel = staticmethod(_stronge_kernel)

    def __post_init__(self):
        require_positive("effective_modulus", self.effective_modulus, "Pa")
        require_positive("radius", self.radius, "m")
        require_positive("yield_strength", self.yield_strength, "Pa")
        require_positive("yield_pressure_factor", self.yield_pressure_factor)
        require_in_range("plastic_indentation_ratio", self.plastic_indentation_ratio, 1.0, np.inf,
                         low_inclusive=False)
        minimum = float(np.max(2.0 / 3.0 * np.asarray(self.yield_pressure_factor, float)))
        require_in_range("plastic_pressure_factor", self.plastic_pressure_factor, minimum, np.inf,
                         low_inclusive=False)
        stronge_area_law(self.yield_pressure_factor, self.plastic_pressure_factor,
                         self.plastic_indentation_ratio)

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "StrongeContact":
        """E*, R and Y of the pair; ``options`` are the three constants (:meth:`options`)."""
        cls.check_options(options)
        return cls(pair.effective_modulus, pair.effective_radius, pair.required_yield_strength(),
                   **options)

    # -- derived quantities -------------------------------------------------------
    def impact_number(self, impactor_mass, velocity):
        """β [-] of the Yigit–Christoforou law with the same E*, R and Y (seed 001 eq 11), for
        ``impactor_mass`` m_i [kg] and ``velocity`` V0 [m/s]."""
        return reference_impact_number(self.effective_modulus, self.radius, self.yield_strength, impactor_mass,
                                       velocity)

    @property
    def yield_indentation(self):
        """``δ_y = R (π c_y Y / (2E*))²`` [m]."""
        return first_yield_indentation(self.effective_modulus, self.radius, self.yield_strength,
                                       self.yield_pressure_factor)

    @property
    def yield_force(self):
        """``F_y = (4/3) E* R^{1/2} δ_y^{3/2}`` [N]."""
        return first_yield_force(self.effective_modulus, self.radius, self.yield_indentation)

    @property
    def plastic_indentation(self):
        """``δ_p`` [m], onset of the fully plastic regime."""
        return np.asarray(self.plastic_indentation_ratio, float) * self.yield_indentation

    @property
    def continuity_coefficient(self):
        """κ [-] of the elastic-plastic branch (force continuous at δ_p)."""
        return stronge_continuity_coefficient(
            self.yield_pressure_factor, self.plastic_pressure_factor, self.plastic_indentation_ratio
        )

    @property
    def area_law(self):
        """(n, τ) [-] of the elastic-plastic area law ``a²/(R δ_y) = ((δ/δ_y − 1 + τ)/τ)^n``."""
        return stronge_area_law(self.yield_pressure_factor, self.plastic_pressure_factor,
                                self.plastic_indentation_ratio)

    def loading_contact_radius(self, indentation):
        """Contact radius a [m] on the virgin loading curve at indentation δ [m]."""
        delta = np.clip(np.asarray(indentation, dtype=float), 0.0, None)
        radius = np.asarray(self.radius, float)
        yield_delta = self.yield_indentation
        exponent, offset = self.area_law
        u = np.clip((np.minimum(delta, self.plastic_indentation) / yield_delta - 1.0 + offset) / offset, 1.0, None)
        return np.where(delta <= yield_delta, np.sqrt(radius * delta),
                        np.where(delta <= self.plastic_indentation, np.sqrt(radius * yield_delta * u**exponent),
                                 np.sqrt(radius * np.clip(2.0 * delta - yield_delta, 0.0, None))))

    def _recovery(self, max_indentation):
        """Elastic recovery ``δ_m − δ_r = 3F_m/(4E* a_m)`` [m] (= δ_m when elastic; ≤ δ_m)."""
        alpha_max = np.clip(np.asarray(max_indentation, float), 0.0, None)
        force = self.loading_force(alpha_max)
        contact_radius = self.loading_contact_radius(alpha_max)
        with np.errstate(invalid="ignore", divide="ignore"):
            recovery = 3.0 * force / (4.0 * np.asarray(self.effective_modulus, float) * contact_radius)
        elastic = alpha_max <= self.yield_indentation
        return np.where(elastic, alpha_max, np.minimum(recovery, alpha_max))

    def unloading_radius(self, max_indentation):
        """Deformed radius ``R_ℓ = 4E* a_m³/(3F_m)`` [m] of the unloading curve (R if elastic)."""
        alpha_max = np.clip(np.asarray(max_indentation, float), 0.0, None)
        force = self.loading_force(alpha_max)
        contact_radius = self.loading_contact_radius(alpha_max)
        with np.errstate(invalid="ignore", divide="ignore"):
            deformed = 4.0 * np.asarray(self.effective_modulus, float) * contact_radius**3 / (3.0 * force)
        return np.where(alpha_max <= self.yield_indentation, np.asarray(self.radius, float), deformed)

    # -- ContactLaw interface -----------------------------------------------------
    @property
    def kernel_parameters(self) -> np.ndarray:
        plastic_pressure = np.asarray(self.plastic_pressure_factor, float) * np.asarray(self.yield_strength, float)
        exponent, offset = self.area_law
        return np.stack(
            np.broadcast_arrays(
                np.asarray(self.effective_modulus, float),
                np.asarray(self.radius, float),
                self.yield_indentation,
                self.yield_force,
                self.plastic_indentation,
                np.asarray(self.continuity_coefficient, float),
                plastic_pressure,
                exponent,
                offset,
            )
        )

    def permanent_indentation(self, max_indentation):
        """Permanent indentation ``δ_r = δ_m − 3F_m/(4E* a_m)`` [m] (0 if never yielded; ≥ 0)."""
        alpha_max = np.clip(np.asarray(max_indentation, float), 0.0, None)
        return alpha_max - self._recovery(alpha_max)

    def loading_energy(self, max_indentation, points: int = 0):
        """Work [J] to load from 0 to δ_m [m] (closed form, piecewise)."""
        delta = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        yield_delta = self.yield_indentation
        yield_force = self.yield_force
        plastic_delta = self.plastic_indentation
        kappa = np.asarray(self.continuity_coefficient, float)
        exponent, offset = self.area_law
        elastic = 0.4 * yield_force * yield_delta * (np.minimum(delta, yield_delta) / yield_delta) ** 2.5
        u = (np.clip(np.minimum(delta, plastic_delta), yield_delta, None) / yield_delta - 1.0 + offset) / offset
        power = exponent + 1.0
        grown = np.expm1(power * np.log(u))  # u^{n+1} − 1 without cancellation near yield
        elastic_plastic = yield_force * yield_delta * offset * (
            grown / power + exponent / kappa * ((grown + 1.0) * np.log(u) / power - grown / power**2))
        upper = np.clip(delta, plastic_delta, None)
        primitive = lambda d: d**2 - yield_delta * d  # noqa: E731
        plastic = (np.pi * np.asarray(self.radius, float) * np.asarray(self.plastic_pressure_factor, float)
                   * np.asarray(self.yield_strength, float) * (primitive(upper) - primitive(plastic_delta)))
        return elastic + elastic_plastic + plastic

    def recovered_energy(self, max_indentation, points: int = 0):
        """Work [J] returned unloading from δ_m to δ_r (closed form): ``(2/5) F_m (δ_m − δ_r)``."""
        delta = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        return 0.4 * self.loading_force(delta) * self._recovery(delta)
