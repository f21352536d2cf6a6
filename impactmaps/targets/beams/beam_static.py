"""Exact static point compliance of straight beams, every support and theory."""

from __future__ import annotations

from .beam_section import BeamSection

__all__ = ["static_compliance"]


def static_compliance(section: BeamSection, position: float) -> float:
    """Exact static deflection [m/N] at x0 = ``position`` [m] under a unit force at x0.

    Closed forms for every support and theory; free–free beams: the inertia-relief
    compliance of the elastic modes (docs/physics.rst, Static point compliance).
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
