"""Natural modes and static point compliance of straight beams (docs/physics_contract.md §3.2).

One import path for the closed-form SS modes, the classical Euler modes, the p-version
finite-element modes (Rayleigh, Timoshenko), the exact static compliance and the section
types. Equations, methods and accuracy: docs/physics.rst (Beam targets).
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
