"""Natural modes and static point compliance of straight beams (docs/physics_contract.md §3.2).

The beam occupies ``0 ≤ x ≤ L``. Its section is described by five numbers, so that
isotropic and specially orthotropic beams share one code path:

``bending_stiffness`` bD11 (= EI) [N·m²], ``shear_stiffness`` S = k b A55 (= kGA) [N],
``mass_per_length`` ρA [kg/m], ``rotary_inertia`` ρI [kg·m].

Equations of motion (seed 001 (16)–(17)), ψ the section rotation, ``ψ + w'`` the shear
strain, bending moment ``M = bD11 ψ'``, shear force ``Q = S (ψ + w')``::

    bD11 ψ'' − S (ψ + w') = ρI ψ̈,        S (ψ' + w'') + p = ρA ẅ.

Theories: ``"euler"`` (S → ∞, ρI → 0, so ψ = −w'), ``"rayleigh"`` (S → ∞, ρI kept),
``"timoshenko"`` (both). Supports, end x = 0 first: ``"ss"``, ``"cc"``, ``"cs"``,
``"cf"`` (cantilever, free at x = L), ``"ff"``. Clamped: w = ψ = 0; simply supported:
w = 0, M = 0; free: M = 0, Q = 0.

Modes are mass-normalised, ``∫ (ρA W_i W_j + ρI Ψ_i Ψ_j) dx = δ_ij`` (ρI = 0 for Euler).
Three families of mode sets are produced here, each as an object with ascending
``frequencies`` [rad/s] and methods ``deflection(points, count)`` (W_j) and
``rotation(points, count)`` (Ψ_j):

* :func:`simply_supported_modes` — closed form, every theory, fully vectorised
  (:mod:`~impactmaps.targets.beams.beam_sine_modes`);
* :func:`classical_euler_modes` — Euler beams with any support: roots of the classical
  frequency equations (Blevins 1979, Table 8-1) by bisection on overflow-free forms, and
  mode shapes in the bounded basis ``cos βx, sin βx, e^{−βx}, e^{−β(L−x)}`` (accurate for
  any mode number) (:mod:`~impactmaps.targets.beams.beam_euler_modes`);
* :func:`finite_element_modes` — Rayleigh and Timoshenko beams with supports other than
  SS: a hierarchical p-version finite-element model (see that function for method and
  accuracy), cached per section and mesh (:mod:`~impactmaps.targets.beams.beam_fe_modes`,
  eigen-solution in :mod:`~impactmaps.targets.beams.beam_fe_eigen`).

:func:`static_compliance` (:mod:`~impactmaps.targets.beams.beam_static`) gives the exact point
compliance for every support and theory; :class:`BeamSection`, :class:`ModeSet` and
:func:`largest_wavenumber` live in :mod:`~impactmaps.targets.beams.beam_section`. This module
gathers them under one import path.
"""


from __future__ import annotations

from .beam_euler_modes import classical_euler_modes, euler_roots
from .beam_fe_modes import (FE_DEGREE, FE_MAX_DOFS, FE_RESOLUTION, finite_element_mode_count, finite_element_modes,
                            finite_element_resolution_limit)
from .beam_section import BeamSection, ModeSet, largest_wavenumber
from .beam_sine_modes import simply_supported_count, simply_supported_modes
from .beam_static import static_compliance
from ..options import BEAM_SUPPORTS as SUPPORTS
from ..options import BEAM_THEORIES as THEORIES

__all__ = [
    "SUPPORTS",
    "THEORIES",
    "BeamSection",
    "ModeSet",
    "largest_wavenumber",
    "euler_roots",
    "simply_supported_modes",
    "simply_supported_count",
    "classical_euler_modes",
    "finite_element_modes",
    "finite_element_mode_count",
    "finite_element_resolution_limit",
    "static_compliance",
    "FE_DEGREE",
    "FE_RESOLUTION",
    "FE_MAX_DOFS",
]
