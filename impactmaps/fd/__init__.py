"""Finite-difference Rayleigh beam with a layered elastic-plastic cross-section (seed 000).

:mod:`.section` — the layered section (stress update, moment, moment–curvature);
:mod:`.beam` — the beam grid, supports, the compiled time loop, the impact solver
:func:`simulate_fd` and the prescribed-load solver :func:`simulate_fd_response`.
"""

from .beam import (
    STANDARD_GRAVITY,
    FDBeam,
    FDDetails,
    FDResponse,
    grid_frequency_bound,
    simulate_fd,
    simulate_fd_response,
    stable_time_step,
)
from .section import (
    LayeredSection,
    SectionState,
    rectangular_moment_curvature,
    stress_update,
)

__all__ = [
    "FDBeam",
    "FDDetails",
    "FDResponse",
    "LayeredSection",
    "STANDARD_GRAVITY",
    "SectionState",
    "grid_frequency_bound",
    "rectangular_moment_curvature",
    "simulate_fd",
    "simulate_fd_response",
    "stable_time_step",
    "stress_update",
]
