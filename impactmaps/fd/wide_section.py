"""Wide-section model of the layered FD beam: the plastic hinge held across its width.

A saturating kinematic back stress raises a wide section's fully plastic moment towards
``(σ_y + β_sat) b h²/4``, calibrated on 3D FE for 1 ≤ b/h ≤ :data:`CALIBRATED_RATIO`
(``validation/fe/level5_wide_calibration.py``). Model and figures: docs/fd_beam.rst.
"""

from __future__ import annotations

import math

__all__ = ["CALIBRATED_RATIO", "CONSTRAINT_STRAIN_RATIO", "EDGE_LENGTH", "NARROW_RATIO",
           "PLANE_STRAIN_FACTOR", "constraint_fraction", "constraint_parameters"]

#: Plane-strain over uniaxial yield stress (von Mises, no plastic lateral strain): 2/√3.
PLANE_STRAIN_FACTOR = 2.0 / math.sqrt(3.0)
#: λ: decay length of the lateral restraint from a free side face, in units of h (fitted).
EDGE_LENGTH = 0.72
#: n_c: the constraint develops over a plastic strain ε_c = n_c σ_y/E (fitted).
CONSTRAINT_STRAIN_RATIO = 0.78
#: At and below this width/height the section is the uniaxial one (no constraint).
NARROW_RATIO = 1.0
#: Largest width/height of the calibration (3D limit loads and static curves).
CALIBRATED_RATIO = 8.63


def _restraint(ratio: float) -> float:
    """φ(b/h) = 1 − tanh(u)/u, u = (b/h)/(2λ): width-averaged lateral restraint [-]."""
    u = ratio / (2.0 * EDGE_LENGTH)
    return 1.0 - math.tanh(u) / u


def constraint_fraction(width: float, height: float) -> float:
    """Fraction ``φ(b/h) − φ(1)`` ≥ 0 [-] of the plane-strain gain carried by a ``width`` × ``height`` [m] section."""
    ratio = float(width) / float(height)
    if ratio <= NARROW_RATIO:
        return 0.0
    return _restraint(ratio) - _restraint(NARROW_RATIO)


def constraint_parameters(width, height, youngs_modulus, yield_strength):
    """The width constraint ``(β_sat [Pa], γ [-])`` of a b × h [m] section of E, σ_y [Pa]; (0, 0) for b/h ≤ 1."""
    fraction = constraint_fraction(width, height)
    if fraction <= 0.0:
        return 0.0, 0.0
    saturation = (PLANE_STRAIN_FACTOR - 1.0) * yield_strength * fraction
    return saturation, youngs_modulus / (CONSTRAINT_STRAIN_RATIO * yield_strength)
