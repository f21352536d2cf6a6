"""Finite-difference Rayleigh beam with a layered elastic-plastic cross-section (seed 000).

:func:`simulate_fd` (impact), :func:`simulate_fd_response` (prescribed load),
:class:`FDBeam`, :class:`FDSettings`, :func:`stable_time_step`. Model: docs/fd_beam.rst.
"""

from .beam import FDBeam, FDSettings
from .grid import grid_frequency_bound
from .impact import STANDARD_GRAVITY, FDDetails, simulate_fd
from .response import FDResponse, simulate_fd_response
from .section import (
    LayeredSection,
    SectionState,
    rectangular_moment_curvature,
    stress_update,
)
from .timestep import stable_time_step

__all__ = [
    "FDBeam",
    "FDDetails",
    "FDResponse",
    "FDSettings",
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
