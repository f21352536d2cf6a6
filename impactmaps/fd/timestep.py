"""Time step of the explicit finite-difference scheme: stability limit and contact resolution.

``Δt ≤ 2/sqrt(λ* + k_c (M⁻¹_kk + 1/m))``; the default step is ``safety × limit``, capped at
``0.1/ω_c`` (docs/fd_beam.rst).
"""

from __future__ import annotations

import math

import numpy as np

from .._checks import require_in_range, require_positive
from ..contact.base import ContactLaw
from .energy import kernel_curve
from .grid import beam_grid, inverse_mass_at, node_for

__all__ = ["choose_time_step", "contact_rate", "single_case_parameters", "stable_time_step"]

#: Default time step never exceeds this fraction of 1/ω_c (ω_c: contact–node frequency at
#: the expected peak stiffness), i.e. ≥ 60 steps per contact oscillation period.
_CONTACT_RESOLUTION = 0.1


def single_case_parameters(law: ContactLaw, caller: str) -> np.ndarray:
    """``law.kernel_parameters`` as a contiguous 1-D float array (``ValueError`` for a batch)."""
    params = np.ascontiguousarray(np.asarray(law.kernel_parameters, dtype=float))
    if params.ndim != 1:
        raise ValueError(
            f"law.kernel_parameters has shape {params.shape}: {caller} needs a single case "
            "(1-D parameters), not a batch"
        )
    return params


def contact_stiffness_bound(law: ContactLaw, params, impactor_mass: float, velocity: float) -> float:
    """Largest tangent contact stiffness [N/m] expected in the impact (at twice its energy)."""
    target = 2.0 * 0.5 * impactor_mass * velocity**2
    reach = float(law.indentation_for_energy(target))
    alpha = 1e-12 * 2.0 ** max(0, math.ceil(math.log2(reach / 1e-12)))
    grid = alpha * np.linspace(0.0, 1.0, 4097)[1:]
    _f, loading = kernel_curve(law.kernel, params, grid, grid)
    _f, unloading = kernel_curve(law.kernel, params, grid * (1.0 - 1e-12), np.full(grid.size, alpha))
    bound = float(max(np.max(loading), np.max(unloading)))
    if not np.isfinite(bound):
        raise ValueError(f"law = {law!r} returns a non-finite tangent stiffness up to α = {alpha:g} m")
    return bound


def contact_rate(grid, node, law, params, impactor_mass, velocity):
    """(k_c, k_c (M⁻¹_kk + 1/m)): contact stiffness bound [N/m] and its frequency² [1/s²]."""
    stiffness = contact_stiffness_bound(law, params, impactor_mass, velocity)
    return stiffness, stiffness * (inverse_mass_at(grid, node) + 1.0 / impactor_mass)


def choose_time_step(grid, time_step, safety_factor, rate):
    """(time step, stability limit) [s]; a forced ``time_step`` above the limit is a ``ValueError``."""
    require_in_range("safety_factor", safety_factor, 0.0, 1.0, low_inclusive=False)
    limit = 2.0 / math.sqrt(grid.max_eigenvalue + rate)
    if time_step is None:
        step = safety_factor * limit
        if rate > 0:
            step = min(step, _CONTACT_RESOLUTION / math.sqrt(rate))
        return step, limit
    require_in_range("time_step", time_step, 0.0, limit, low_inclusive=False, unit="s")
    return float(time_step), limit


def stable_time_step(beam, law: ContactLaw, impactor_mass, velocity, impact_position=None,
                     safety_factor=0.8):
    """The default time step and the stability limit [s] of :func:`~impactmaps.fd.simulate_fd`
    (arguments as there)."""
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    params = single_case_parameters(law, "stable_time_step")
    grid = beam_grid(beam)
    _x0, node = node_for(beam, grid, impact_position, "impact_position")
    _k, rate = contact_rate(grid, node, law, params, float(impactor_mass), float(velocity))
    return choose_time_step(grid, None, safety_factor, rate)
