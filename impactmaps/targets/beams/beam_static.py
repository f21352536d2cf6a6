"""Exact static point compliance of straight beams, every support and theory."""

from __future__ import annotations

from .beam_section import BeamSection

__all__ = ["static_compliance"]


def static_compliance(section: BeamSection, position: float) -> float:
    """Exact static deflection [m/N] at x0 = ``position`` under a unit force at x0.

    Closed forms (a = x0, b = L − x0, s = 1/S the shear compliance, zero for Euler and
    Rayleigh, Φ = 12 EI s/L²), all derived from the static equations of docs/physics_contract.md §3.2
    with a point load (unit-load method) and checked symbolically:

    * ss: ``a²b²/(3EIL) + s a b/L`` (docs/physics_contract.md §3.2);
    * cc: ``a b [a²b² + (Φ L²/4)(L² + ab) + Φ² L⁴/4] / (3 EI L³ (1 + Φ))``; Φ = 0 gives
      ``a³b³/(3EIL³)``, the centre gives ``L³/(192EI) + L/(4S)``;
    * cs (clamped at x = 0): ``a b [a²b(3L + b) + Φ L²(L² + ab) + Φ² L⁴/4] / (3 EI L³ (4 + Φ))``;
      Φ = 0 gives ``a³b²(3L + b)/(12EIL³)``;
    * cf (clamped at x = 0, free at L): ``a³/(3EI) + s a``;
    * ff: the beam is unrestrained, so the static compliance is defined by inertia
      relief — the compliance of the *elastic* modes only, ``Σ_elastic W_j(x0)²/ω_j²``
      (the rigid-body modes are excluded): the deflection, made mass-orthogonal to the
      rigid-body modes, under the unit force balanced by the d'Alembert loads of the
      rigid-body acceleration. With t = x0/L − ½, r = ρI/(ρA L²), σ = EI s/L²::

          (EI/L³)·C = [P00 + r P01 + r² P02 + σ (P10 + r P11 + r² P12)] / (6720 (1 + 12r)²)
          P00 = −1344t⁶ + 2800t⁴ − 444t² + 21,   P01 = −168(96t⁶ − 320t⁴ + 54t² − 3),
          P02 = 1008(240t⁴ − 40t² + 3),          P10 = 112(240t⁴ − 48t² + 5),
          P11 = 13440(24t⁴ − 6t² + 1),           P12 = 80640(12t² + 1);

      e.g. Euler: L³/(320EI) at the centre and L³/(105EI) at an end. ρI enters through
      the rigid-body rotation mode (Rayleigh and Timoshenko).
    """
    L, EI = section.length, section.bending_stiffness
    s = section.shear_compliance
    a = float(position)
    b = L - a
    supports = section.supports
    if supports == "ss":
        return a * a * b * b / (3.0 * EI * L) + s * a * b / L
    if supports == "cf":
        return a**3 / (3.0 * EI) + s * a
    phi = 12.0 * EI * s / L**2
    if supports == "cc":
        numerator = a * a * b * b + 0.25 * phi * L * L * (L * L + a * b) + 0.25 * phi**2 * L**4
        return a * b * numerator / (3.0 * EI * L**3 * (1.0 + phi))
    if supports == "cs":
        numerator = (a * a * b * (3.0 * L + b) + phi * L * L * (L * L + a * b)
                     + 0.25 * phi**2 * L**4)
        return a * b * numerator / (3.0 * EI * L**3 * (4.0 + phi))
    if supports == "ff":
        t2 = (a / L - 0.5) ** 2
        r = section.rotary_inertia / (section.mass_per_length * L * L)
        sigma = EI * s / (L * L)
        p00 = ((-1344.0 * t2 + 2800.0) * t2 - 444.0) * t2 + 21.0
        p01 = -168.0 * (((96.0 * t2 - 320.0) * t2 + 54.0) * t2 - 3.0)
        p02 = 1008.0 * ((240.0 * t2 - 40.0) * t2 + 3.0)
        p10 = 112.0 * ((240.0 * t2 - 48.0) * t2 + 5.0)
        p11 = 13440.0 * ((24.0 * t2 - 6.0) * t2 + 1.0)
        p12 = 80640.0 * (12.0 * t2 + 1.0)
        value = (p00 + r * (p01 + r * p02) + sigma * (p10 + r * (p11 + r * p12))) / (
            6720.0 * (1.0 + 12.0 * r) ** 2)
        return L**3 / EI * value
    raise ValueError(f"supports = {supports!r} is not known")
