"""The Kirchhoff Rayleigh–Ritz side of a rectangular plate (edges other than SSSS): its modes
and its classical static point compliance (the Navier series corrected by the Ritz basis).
:class:`impactmaps.targets.plates.plate.Plate` chooses between these and the Navier solution.
"""

from __future__ import annotations

import functools
import warnings

import numpy as np

from . import basis_cache, ritz
from ..base import ModalBasis
from .plate_static import navier_static_compliance

__all__ = ["STATIC_RITZ_FUNCTIONS", "classical_static_compliance", "ritz_plate_modes"]

#: Ritz functions per direction for the static point compliance of non-SSSS plates.
#: Must be ≥ :data:`impactmaps.targets.plates.ritz.MAX_FUNCTIONS` so that the static basis
#: contains every modal basis (then the residual compliance is never negative).
STATIC_RITZ_FUNCTIONS = 40


def ritz_plate_modes(plate, max_frequency: float, min_modes: int):
    """(:class:`ModalBasis`, mode-shape function of points) of a plate whose edges are not all
    simply supported: the Kirchhoff Rayleigh–Ritz basis (:mod:`impactmaps.targets.plates.ritz`), grown
    until it resolves ``min_modes`` or reaches its cap; warns when ``max_frequency`` [rad/s]
    is beyond what the largest basis resolves (:meth:`impactmaps.targets.plates.plate.Plate.modes`)."""
    args = (plate.length_x, plate.length_y, plate.D11, plate.D22, plate.D12, plate.D66, plate.mass_per_area)
    sizing_frequency = max_frequency
    while True:
        n_x, n_y, required_x, required_y = ritz.ritz_basis_size(sizing_frequency, *args)
        solution = ritz.solve_ritz_plate(*args, plate.edges, n_x, n_y)
        resolved_count = int(np.sum(solution.frequencies <= solution.resolved_frequency))
        at_cap = n_x == ritz.MAX_FUNCTIONS and n_y == ritz.MAX_FUNCTIONS
        if resolved_count >= min_modes or at_cap:
            break
        sizing_frequency = max(1.5 * sizing_frequency, float(solution.frequencies[min_modes - 1]))
    if max_frequency > solution.resolved_frequency:
        warnings.warn(
            f"max_frequency = {max_frequency:.6g} rad/s exceeds what the largest Ritz basis "
            f"({n_x}×{n_y} functions; {required_x}×{required_y} would be needed) resolves, "
            f"{solution.resolved_frequency:.6g} rad/s: modes above that are represented by "
            "the residual compliance only", stacklevel=4)
    count = int(np.sum(solution.frequencies <= min(max_frequency, solution.resolved_frequency)))
    count = max(count, min(min_modes, solution.frequencies.size))
    if count > resolved_count:
        warnings.warn(
            f"min_modes = {min_modes} exceeds the {resolved_count} modes the largest Ritz "
            "basis resolves; the higher modes returned are not converged", stacklevel=4)
    omega = np.asarray(solution.frequencies[:count])
    participation = solution.mode_shapes(np.array([plate.impact_point]), count)[0]
    basis = ModalBasis.from_modes(omega, participation, plate.static_compliance(),
                                  np.full(omega.shape, float(plate.damping_ratio)))

    def shape_function(points):
        return solution.mode_shapes(points, count)

    return basis, shape_function


@functools.lru_cache(maxsize=32)
def classical_static_compliance(length_x, length_y, D11, D22, D12, D66, edges, impact_point) -> float:
    """Classical point compliance [m/N] of a plate with any edges (:meth:`Plate.static_compliance`).

    Parameters as the fields of :class:`Plate` (sides [m], bending stiffnesses [N·m], the
    edge code and the impact point (x0, y0) [m]); cached (a pure function of numbers).
    """
    navier = navier_static_compliance(length_x, length_y, D11, D22, D12, D66, impact_point)
    if edges == "SSSS":
        return navier
    args = (length_x, length_y, D11, D22, D12, D66)
    n = max(STATIC_RITZ_FUNCTIONS, ritz.MAX_FUNCTIONS)  # must contain every modal basis

    def solve():  # two dense Cholesky factors (~0.4 s): kept on disk (basis_cache)
        return {"compliances": np.array([ritz.ritz_static_compliance(*args, e, impact_point, n, n)
                                         for e in (edges, "SSSS")])}

    inputs = {"plate": args, "edges": edges, "impact_point": tuple(impact_point), "functions": n}
    ritz_edges, ritz_ssss = (float(c) for c in basis_cache.cached_arrays("ritz-compliance", inputs, solve)["compliances"])
    return ritz_edges + (navier - ritz_ssss)
