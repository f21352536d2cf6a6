"""Wide-section model of the layered FD beam: the plastic hinge held across its width.

Why
---
The layers of :class:`~impactmaps.fd.section.LayeredSection` are in uniaxial stress, so
the section's fully plastic moment is ``M_p = σ_y b h²/4`` whatever its width. In a 3D
beam a yielding layer wants to change its width by ``−½ dε_p`` (plastic flow keeps the
volume), unlike its elastic neighbours; a wide beam's interior cannot, a lateral stress
``σ_yy`` builds up and the axial stress the layer carries rises towards the plane-strain
value ``2σ_y/√3`` (von Mises, ``σ_yy = σ_xx/2``), while near the free side faces
``σ_yy → 0``. Against the project's own 3D elastic–perfectly-plastic CalculiX beams
(``validation/fe/level5_static_bending.py``: quarter beams, C3D20R, the strip-loaded
3-point bending of FE level 5) the static limit load grows with b/h: 1.540, 1.571, 1.631
(1.633 with two elements across the half width), 1.715, 1.760 P_y at b/h = 0.36, 1.0, 2.16,
4.32, 8.63, against 1.507 P_y of the uniaxial beam theory (docs/validation.rst, FE level 5).

Model
-----
Each layer's back stress gets a *constraint part* β_c with Armstrong–Frederick evolution
(:func:`~impactmaps.fd.section.return_map`): ``dβ_c = (β_sat sign(dε_p) − β_c) |dε_p| / ε_c``,
i.e. the yield stress of a layer loaded monotonically rises from σ_y towards
``σ_y + β_sat`` over a plastic strain of a few ε_c, and the fully plastic moment tends to
``(σ_y + β_sat) b h²/4``. Kinematic, because the lateral stress is locked in the layer
when it unloads (a layer at plane strain whose lateral stress σ_yy = σ_y/√3 stays locked
re-yields in reverse at −0.58 σ_y; the kinematic form: −0.85 σ_y; an isotropic one would
give −1.15 σ_y). The elastic response and first yield are untouched. The two parameters:

* ``β_sat = (2/√3 − 1) σ_y [φ(b/h) − φ(1)]`` (0 for b/h ≤ 1: today's uniaxial model,
  validated there against 3D, FE level 5), with the width-averaged restraint of a lateral
  stress that vanishes at the free faces and decays into the width as in a shear-lag
  (boundary-layer) problem, ``σ_yy ∝ 1 − cosh(y/(λh))/cosh(b/(2λh))``, whose average is
  ``φ(b/h) = 1 − tanh(u)/u``, ``u = b/(2λh)`` — a form chosen here, not taken from a
  publication. λ = :data:`EDGE_LENGTH` is fitted to the 3D limit loads above (with a free
  baseline, the 3D strip-loaded beam's own +2.6 % over beam theory at b → 0).
* ``ε_c = n_c σ_y / E`` with n_c = :data:`CONSTRAINT_STRAIN_RATIO`, fitted to the 3D
  static load–deflection curves at b/h = 2.16, 4.32 and 8.63 up to 1.5 P_y (where the
  narrow 3D beam follows beam theory). The ``σ_y/E`` scaling is that of a fully
  restrained layer (initial slope ``E/(4(1 − ν²))``: ε_c = 0.56 σ_y/E); it was calibrated
  on one steel (S235, ν = 0.3) only.

Against the 3D beam under two impact force histories (FE level 5, seed-000 beam, b/h 2.16)
the FD peak deflection is within 2 % and the permanent deflection within −5 … +10 % (the
uniaxial section: +6 … +12 % and +23 … +39 %).

Calibrated for 1 ≤ b/h ≤ :data:`CALIBRATED_RATIO`; the FD impact warns
(:class:`~impactmaps.validity.ModelValidityWarning`) when a section outside it yields.
The calibration is ``validation/fe/level5_wide_calibration.py``
(``results/level5_wide_calibration.json``; a test checks these constants against it).
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
    """Fraction of the plane-strain gain carried by a b × h section, ``φ(b/h) − φ(1)`` ≥ 0.

    Parameters
    ----------
    width, height : float
        Section width b and height h [m].

    Returns
    -------
    float
        0 for b/h ≤ :data:`NARROW_RATIO`; tends to ``1 − φ(1)`` for b ≫ h [-].
    """
    ratio = float(width) / float(height)
    if ratio <= NARROW_RATIO:
        return 0.0
    return _restraint(ratio) - _restraint(NARROW_RATIO)


def constraint_parameters(width, height, youngs_modulus, yield_strength):
    """The width constraint of a layered section: ``(β_sat [Pa], γ = 1/ε_c [-])``.

    Parameters
    ----------
    width, height : float
        Section width b and height h [m].
    youngs_modulus, yield_strength : float
        E and σ_y [Pa].

    Returns
    -------
    tuple of float
        ``β_sat = (2/√3 − 1) σ_y (φ(b/h) − φ(1))`` [Pa] and ``γ = E / (n_c σ_y)`` [-];
        ``(0.0, 0.0)`` for b/h ≤ 1.
    """
    fraction = constraint_fraction(width, height)
    if fraction <= 0.0:
        return 0.0, 0.0
    saturation = (PLANE_STRAIN_FACTOR - 1.0) * yield_strength * fraction
    return saturation, youngs_modulus / (CONSTRAINT_STRAIN_RATIO * yield_strength)
