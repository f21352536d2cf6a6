"""The named choices of the targets, written once: structure kinds, theories, supports.

Every module that validates or lists these (targets, map structures, case files, the
command line) imports them from here.
"""

from __future__ import annotations

__all__ = ["STRUCTURE_KINDS", "BEAM_THEORIES", "BEAM_SUPPORTS", "PLATE_THEORIES", "CLASSICAL_THEORIES",
           "DIVERGENT_POINT_LOAD_THEORIES"]

#: Kinds of finite structure with modes and an infinite-structure asymptote.
STRUCTURE_KINDS = ("beam", "plate")
#: Beam theories: Euler–Bernoulli, Rayleigh (rotary inertia), Timoshenko (and shear).
BEAM_THEORIES = ("euler", "rayleigh", "timoshenko")
#: Beam support codes, end x = 0 first: s = simply supported, c = clamped, f = free.
BEAM_SUPPORTS = ("ss", "cc", "cs", "cf", "ff")
#: Plate theories: classical (shear-rigid, no rotary inertia) and Mindlin (first-order shear).
PLATE_THEORIES = ("kirchhoff", "mindlin")
#: Theories whose infinite-structure closed forms are the toolkit's asymptotes (the Euler
#: beam's t^(-1/2) kernel, the Kirchhoff plate's dashpot 8 sqrt(D ρh)).
CLASSICAL_THEORIES = ("euler", "kirchhoff")
#: Theories under which the deflection under a point load is unbounded (a Mindlin plate:
#: logarithmic, from transverse shear), so a point-load peak force never converges.
DIVERGENT_POINT_LOAD_THEORIES = ("mindlin",)
