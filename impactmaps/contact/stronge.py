"""The "refined Stronge" elastic-plastic sphere contact law (PHYSICS.md §2, seed 000).

Sphere of radius R on a flat of yield stress Y, effective modulus E*:

* elastic, ``δ ≤ δ_y``: Hertz, ``F = (4/3) E* R^{1/2} δ^{3/2}``, ``a² = R δ``; first yield
  when the Hertz peak pressure ``p0 = (2E*/π) sqrt(δ/R)`` reaches ``c_y Y``:
  ``δ_y = R (π c_y Y / (2E*))²``, ``F_y = (4/3) E* R^{1/2} δ_y^{3/2}``;
* elastic-plastic, ``δ_y < δ ≤ δ_p``: ``a² = R (2δ − δ_y)``,
  ``F = F_y (2δ/δ_y − 1) [1 + ln(2δ/δ_y − 1)/κ]``;
* fully plastic, ``δ > δ_p``: mean pressure ``c_p Y``, ``F = π a² c_p Y``;
* κ makes the force continuous at ``δ_p``:
  ``κ = ln(2δ_p/δ_y − 1) / (3c_p/(2c_y) − 1)`` (3.1495 with the defaults);
* unloading from ``(δ_m, F_m, a_m)``: Hertz with the deformed radius
  ``R_ℓ = 4E* a_m³/(3F_m)`` about the permanent indentation
  ``δ_r = δ_m − 3F_m/(4E* a_m)``, i.e. ``F = F_m ((δ − δ_r)/(δ_m − δ_r))^{3/2}``;
  reloading retraces it up to ``δ_m``.

Sources of the default constants
--------------------------------
``c_y = 1.6``: first yield under a frictionless sphere (von Mises, ν ≈ 0.3) when the
Hertz peak pressure is ``p0 ≈ 1.60 Y`` (Johnson, *Contact Mechanics*, CUP 1985, §6.2).
``c_p = 2.8``: mean pressure of a fully plastic spherical indentation, ``p_m ≈ 2.8–3 Y``
(Tabor's hardness relation; Johnson 1985, §6.3–6.4). ``δ_p/δ_y = 84``: the ratio of the
refined Stronge model as specified in PHYSICS.md, which attributes it to Stronge
(*Impact Mechanics*, CUP 2000, ch. 4). We could not check 84 (nor the exact choice 2.8
rather than 3) against the printed books; treat them as the specification's defaults,
not as verified literature numbers. 1.60 is the standard von Mises value.

Known defect (see the tests and the report)
-------------------------------------------
As specified, just above yield the elastic-plastic loading curve is *stiffer* than the
elastic unloading curve that leaves it: the tangent jumps at ``δ_y`` from
``1.5 F_y/δ_y`` to ``2(1 + 1/κ) F_y/δ_y``, and the elastic recovery
``3F_m/(4E* a_m)`` grows faster than ``δ_m`` (``δ_r ≈ −(2/κ)(δ_m − δ_y)`` near yield).
For ``δ_y < δ_m < 4.897 δ_y`` a load–unload cycle therefore *returns more work than it
absorbed* (negative dissipation, restitution ``e > 1``, up to 1.158 at ``δ_m ≈ 1.6 δ_y``), and for
``δ_m < 5.40 δ_y`` the computed ``δ_r`` is negative (the unloading curve still carries
force at ``δ = 0``, where the no-tension rule cuts it to zero). The law is implemented
exactly as specified; :attr:`StrongeContact.energy_consistent_indentation` gives the
smallest ``δ_m`` above which the dissipation is non-negative.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numba
import numpy as np

from .._checks import require_in_range, require_positive
from .base import ContactLaw, law_option, register_contact_law
from .yigit_christoforou import YigitChristoforouContact

__all__ = ["StrongeContact", "stronge_continuity_coefficient"]

#: Default ``c_y``: Hertz peak pressure at first yield ``p0 = 1.60 Y`` (Johnson 1985, §6.2).
DEFAULT_YIELD_PRESSURE_FACTOR = 1.6
#: Default ``c_p``: fully plastic mean pressure ``p_m ≈ 2.8 Y`` (Tabor; Johnson 1985, §6.3).
DEFAULT_PLASTIC_PRESSURE_FACTOR = 2.8
#: Default ``δ_p/δ_y`` of the refined Stronge model (PHYSICS.md §2; not verified in print).
DEFAULT_PLASTIC_INDENTATION_RATIO = 84.0


def stronge_continuity_coefficient(
    yield_pressure_factor=DEFAULT_YIELD_PRESSURE_FACTOR,
    plastic_pressure_factor=DEFAULT_PLASTIC_PRESSURE_FACTOR,
    plastic_indentation_ratio=DEFAULT_PLASTIC_INDENTATION_RATIO,
):
    """``κ = ln(2δ_p/δ_y − 1) / (3c_p/(2c_y) − 1)`` [-]: force continuous at ``δ_p``.

    Derivation: at ``δ_p`` the elastic-plastic force ``F_y L [1 + ln L/κ]``
    (``L = 2δ_p/δ_y − 1``) must equal ``π R δ_y L c_p Y``, and
    ``π R δ_y c_p Y / F_y = 3c_p/(2c_y)`` by the definitions of ``δ_y`` and ``F_y``.
    """
    c_y = np.asarray(yield_pressure_factor, float)
    c_p = np.asarray(plastic_pressure_factor, float)
    ratio = np.asarray(plastic_indentation_ratio, float)
    return np.log(2.0 * ratio - 1.0) / (1.5 * c_p / c_y - 1.0)


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
    if delta <= yield_delta:
        root = math.sqrt(delta)
        factor = modulus * math.sqrt(radius)
        return 4.0 / 3.0 * factor * delta * root, 2.0 * factor * root, math.sqrt(radius * delta)
    ratio = 2.0 * delta / yield_delta - 1.0
    contact_radius = math.sqrt(radius * (2.0 * delta - yield_delta))
    if delta <= plastic_delta:
        log_ratio = math.log(ratio)
        force = yield_force * ratio * (1.0 + log_ratio / kappa)
        stiffness = 2.0 * yield_force / yield_delta * (1.0 + (1.0 + log_ratio) / kappa)
        return force, stiffness, contact_radius
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
    recovery = 3.0 * peak_force / (4.0 * params[0] * peak_radius)  # δ_m − δ_r
    gap = alpha - (alpha_max - recovery)
    if gap <= 0.0:
        return 0.0, 0.0
    scale = peak_force / (recovery * math.sqrt(recovery))
    root = math.sqrt(gap)
    return scale * gap * root, 1.5 * scale * root


@register_contact_law
@dataclass(frozen=True)
class StrongeContact(ContactLaw):
    """Refined Stronge elastic-plastic sphere–flat contact (PHYSICS.md §2).

    Parameters
    ----------
    effective_modulus : float or array_like
        E* [Pa] (seed 001 eq 8).
    radius : float or array_like
        Sphere (effective) radius R [m].
    yield_strength : float or array_like
        Yield stress Y of the softer material [Pa].
    yield_pressure_factor : float or array_like, default 1.6
        ``c_y``: Hertz peak pressure at first yield is ``c_y Y`` (Johnson 1985, §6.2).
    plastic_pressure_factor : float or array_like, default 2.8
        ``c_p``: fully plastic mean contact pressure is ``c_p Y`` (Johnson 1985, §6.3);
        must exceed ``2c_y/3`` (the mean Hertz pressure at yield) so that κ > 0.
    plastic_indentation_ratio : float or array_like, default 84
        ``δ_p/δ_y``, onset of the fully plastic regime (> 1).

    Notes
    -----
    See the module docstring for the equations, the sources of the defaults, and the
    energy defect of the specified law just above yield.
    """

    effective_modulus: float
    radius: float
    yield_strength: float
    yield_pressure_factor: float = law_option(
        DEFAULT_YIELD_PRESSURE_FACTOR, "", "c_y: the Hertz peak pressure at first yield is c_y Y")
    plastic_pressure_factor: float = law_option(
        DEFAULT_PLASTIC_PRESSURE_FACTOR, "", "c_p: the fully plastic mean contact pressure is c_p Y (> 2 c_y/3)")
    plastic_indentation_ratio: float = law_option(
        DEFAULT_PLASTIC_INDENTATION_RATIO, "", "δ_p/δ_y: onset of the fully plastic regime (> 1)")

    name: ClassVar[str] = "stronge"
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

    @classmethod
    def from_contact_pair(cls, pair, **options) -> "StrongeContact":
        """E*, R and Y of the pair; ``options`` are the three constants (:meth:`options`)."""
        cls.check_options(options)
        return cls(pair.effective_modulus, pair.effective_radius, pair.required_yield_strength(),
                   **options)

    # -- derived quantities -------------------------------------------------------
    def impact_number(self, impactor_mass, velocity):
        """β [-] of the Yigit–Christoforou law with the same E*, R and Y (seed 001 eq 11).

        ``β = V0/(ω α_y)`` with ``α_y = 0.68 π² Y² R/E*²`` (eq 9) and
        ``ω = sqrt(K_h α_y^{1/2}/m_i)`` — not this law's own δ_y — so that one β places
        an impact on the restitution chart whichever plastic law is used.

        Parameters
        ----------
        impactor_mass : float or array_like
            m_i [kg].
        velocity : float or array_like
            Impact velocity V0 [m/s].
        """
        reference = YigitChristoforouContact.from_properties(self.effective_modulus, self.radius,
                                                             self.yield_strength)
        return reference.impact_number(impactor_mass, velocity)

    @property
    def yield_indentation(self):
        """``δ_y = R (π c_y Y / (2E*))²`` [m]."""
        return np.asarray(self.radius, float) * (
            np.pi * np.asarray(self.yield_pressure_factor, float) * np.asarray(self.yield_strength, float)
            / (2.0 * np.asarray(self.effective_modulus, float))
        ) ** 2

    @property
    def yield_force(self):
        """``F_y = (4/3) E* R^{1/2} δ_y^{3/2}`` [N]."""
        return (4.0 / 3.0 * np.asarray(self.effective_modulus, float) * np.sqrt(np.asarray(self.radius, float))
                * self.yield_indentation**1.5)

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
    def energy_consistent_indentation(self):
        """Smallest δ_m [m] above which a load–unload cycle dissipates ≥ 0 (see module notes).

        Below it (but above δ_y) the specified law returns more work than it absorbed.
        Found by bisection on the closed-form energies; depends on κ only, through
        ``δ_m/δ_y``.
        """
        yield_delta = self.yield_indentation
        low = np.ones_like(yield_delta)
        high = np.broadcast_to(np.asarray(self.plastic_indentation_ratio, float), yield_delta.shape).copy()
        for _ in range(80):
            mid = 0.5 * (low + high)
            negative = np.asarray(self.dissipated_energy(mid * yield_delta)) < 0.0
            low = np.where(negative, mid, low)
            high = np.where(negative, high, mid)
        return high * yield_delta

    def loading_contact_radius(self, indentation):
        """Contact radius a [m] on the virgin loading curve at indentation δ [m]."""
        delta = np.clip(np.asarray(indentation, dtype=float), 0.0, None)
        radius = np.asarray(self.radius, float)
        yield_delta = self.yield_indentation
        return np.where(delta <= yield_delta, np.sqrt(radius * delta),
                        np.sqrt(radius * np.clip(2.0 * delta - yield_delta, 0.0, None)))

    def _recovery(self, max_indentation):
        """Elastic recovery ``δ_m − δ_r = 3F_m/(4E* a_m)`` [m] (= δ_m when elastic)."""
        alpha_max = np.asarray(max_indentation, float)
        force = self.loading_force(alpha_max)
        contact_radius = self.loading_contact_radius(alpha_max)
        with np.errstate(invalid="ignore", divide="ignore"):
            recovery = 3.0 * force / (4.0 * np.asarray(self.effective_modulus, float) * contact_radius)
        elastic = alpha_max <= self.yield_indentation
        return np.where(elastic, alpha_max, recovery)

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
        return np.stack(
            np.broadcast_arrays(
                np.asarray(self.effective_modulus, float),
                np.asarray(self.radius, float),
                self.yield_indentation,
                self.yield_force,
                self.plastic_indentation,
                np.asarray(self.continuity_coefficient, float),
                plastic_pressure,
            )
        )

    def signed_permanent_indentation(self, max_indentation):
        """``δ_r = δ_m − 3F_m/(4E* a_m)`` [m] as specified — may be negative near yield."""
        alpha_max = np.clip(np.asarray(max_indentation, float), 0.0, None)
        return alpha_max - self._recovery(alpha_max)

    def permanent_indentation(self, max_indentation):
        """Permanent indentation ``max(δ_r, 0)`` [m] (force is zero at and below it)."""
        return np.clip(self.signed_permanent_indentation(max_indentation), 0.0, None)

    def loading_energy(self, max_indentation, points: int = 0):
        """Work [J] to load from 0 to δ_m (closed form, piecewise).

        Elastic ``(2/5) F_y δ_y (δ/δ_y)^{5/2}``; elastic-plastic, with ``L = 2δ/δ_y − 1``,
        ``(F_y δ_y/2) [(L² − 1)/2 + (L² ln L/2 − L²/4 + 1/4)/κ]``; fully plastic
        ``π R c_p Y [δ² − δ_y δ]`` between δ_p and δ_m.
        """
        delta = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        yield_delta = self.yield_indentation
        yield_force = self.yield_force
        plastic_delta = self.plastic_indentation
        kappa = np.asarray(self.continuity_coefficient, float)
        elastic = 0.4 * yield_force * yield_delta * (np.minimum(delta, yield_delta) / yield_delta) ** 2.5
        ratio = 2.0 * np.clip(np.minimum(delta, plastic_delta), yield_delta, None) / yield_delta - 1.0
        elastic_plastic = 0.5 * yield_force * yield_delta * (
            0.5 * (ratio**2 - 1.0) + (0.5 * ratio**2 * np.log(ratio) - 0.25 * ratio**2 + 0.25) / kappa
        )
        upper = np.clip(delta, plastic_delta, None)
        primitive = lambda d: d**2 - yield_delta * d  # noqa: E731
        plastic = (np.pi * np.asarray(self.radius, float) * np.asarray(self.plastic_pressure_factor, float)
                   * np.asarray(self.yield_strength, float) * (primitive(upper) - primitive(plastic_delta)))
        return elastic + elastic_plastic + plastic

    def recovered_energy(self, max_indentation, points: int = 0):
        """Work [J] returned unloading from δ_m (closed form).

        ``(2/5) F_m (δ_m − δ_r)``, less the part below δ = 0 when δ_r < 0 (the
        no-tension rule cuts the curve there).
        """
        delta = np.clip(np.asarray(max_indentation, dtype=float), 0.0, None)
        force = self.loading_force(delta)
        recovery = self._recovery(delta)
        cut = np.clip(-(delta - recovery), 0.0, None)
        with np.errstate(invalid="ignore", divide="ignore"):
            fraction = np.where(recovery > 0.0, (cut / np.where(recovery > 0, recovery, 1.0)) ** 2.5, 0.0)
        return 0.4 * force * recovery * (1.0 - fraction)
