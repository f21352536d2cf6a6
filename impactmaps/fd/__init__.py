"""Finite-difference Rayleigh beam with a layered elastic-plastic cross-section (seed 000).

:mod:`.beam` — the beam (:class:`FDBeam`) and the run options (:class:`FDSettings`);
:mod:`.section` — the layered section (stress update, moment, moment–curvature);
:mod:`.grid` — grid operators, supports, factorisation, the stability bound;
:mod:`._loop` — the compiled time loop (peak refinement shared with the modal solver, :mod:`impactmaps.solvers._peak`);
:mod:`.energy` — the energy ledger; :mod:`.residual` — the permanent deflection;
:mod:`.timestep` — stability limit and default step (:func:`stable_time_step`);
:mod:`.impact` — the impact solver :func:`simulate_fd`;
:mod:`.response` — the prescribed-load solver :func:`simulate_fd_response`.
"""

from .beam import FDBeam, FDSettings
from .grid import grid_frequency_bound
from .impact import STANDARD_GRAVITY, FDDetails, estimate_fd, simulate_fd
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
    "estimate_fd",
    "grid_frequency_bound",
    "rectangular_moment_curvature",
    "simulate_fd",
    "simulate_fd_response",
    "stable_time_step",
    "stress_update",
]
