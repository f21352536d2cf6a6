"""The finite-difference grid of the Rayleigh beam: operators, factorisation, stability.

Nodal equations ``M_mass ẅ + C_d ẇ + f_int(w) = f_ext`` with supports ``"ss"``, ``"cc"``
or ``"free"``; stencils and boundary conditions: docs/fd_beam.rst.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field

import numpy as np

from .._checks import require_in_range

__all__ = [
    "Grid",
    "beam_grid",
    "factorise",
    "gauge_columns",
    "gauge_weights",
    "grid_frequency_bound",
    "inverse_mass_at",
    "node_for",
    "tridiagonal_solve",
]


@dataclass(frozen=True)
class Grid:
    """The grid operators of an :class:`~impactmaps.fd.beam.FDBeam` (built once per beam).

    Attributes: ``n_nodes``; ``dx`` [m]; ``constrained``; ``mass_weight``, ``section_weight``;
    ``stencil`` (3, n) [1/Δx²]; ``mass_diag``/``mass_off`` [kg]; ``damping_diag`` [N s/m];
    ``max_eigenvalue`` λ* [rad²/s²]; ``stiffness_banded`` (3, n) [N/m].
    """

    n_nodes: int
    dx: float
    constrained: np.ndarray  # bool (n,)
    mass_weight: np.ndarray  # translational mass weights m_j
    section_weight: np.ndarray  # c_j
    stencil: np.ndarray  # (3, n): curvature coefficients (left, centre, right), ×1/Δx² later
    mass_diag: np.ndarray
    mass_off: np.ndarray  # (n-1,) coupling j, j+1
    damping_diag: np.ndarray
    max_eigenvalue: float  # rigorous upper bound of λ_max(K_elastic, M_mass)
    stiffness_banded: np.ndarray = field(repr=False)  # (3, n) upper band of K (model EI)

    @property
    def free(self) -> np.ndarray:
        return ~self.constrained

    def stiffness_times(self, w) -> np.ndarray:
        """K w [N] with the banded elastic stiffness (all nodes)."""
        ab = self.stiffness_banded
        out = ab[2] * w
        out[:-1] += ab[1, 1:] * w[1:]
        out[1:] += ab[1, 1:] * w[:-1]
        out[:-2] += ab[0, 2:] * w[2:]
        out[2:] += ab[0, 2:] * w[:-2]
        return out

    def stiffness_dense(self) -> np.ndarray:
        """Dense K [N/m] (all nodes); only for small problems and diagnostics."""
        ab = self.stiffness_banded
        return (np.diag(ab[2]) + np.diag(ab[1, 1:], 1) + np.diag(ab[1, 1:], -1)
                + np.diag(ab[0, 2:], 2) + np.diag(ab[0, 2:], -2))

    def mass_dense(self) -> np.ndarray:
        """Dense M_mass [kg] (all nodes)."""
        return np.diag(self.mass_diag) + np.diag(self.mass_off, 1) + np.diag(self.mass_off, -1)


def grid_frequency_bound(beam) -> float:
    """Rigorous upper bound λ* [rad²/s²] of the highest grid frequency squared (proof: docs/fd_beam.rst)."""
    dx = beam.grid_spacing
    return 16.0 * beam.bending_stiffness / (
        dx**4 * (beam.mass_per_length + 4.0 * beam.rotary_inertia_per_length / dx**2))


#: Float arrays per node a finite-difference run holds besides its layers (the grid's
#: matrices, the loop's state, the residual and response work arrays; rounded up).
NODE_ARRAYS = 40
#: Float arrays per node and section layer (stress, back stress, plastic strain, rate state).
LAYER_ARRAYS = 4


def require_grid_fits(beam) -> None:
    """Refuse (``ValueError`` naming ``n_elements`` and ``n_half_layers``) a grid too large for memory."""
    from ..solvers.run_budget import MEMORY_LIMIT_BYTES

    nodes, layers = beam.n_elements + 1.0, 2.0 * beam.n_half_layers
    state_bytes = nodes * (NODE_ARRAYS + LAYER_ARRAYS * layers) * 8.0
    if state_bytes > MEMORY_LIMIT_BYTES:
        raise ValueError(
            f"n_elements = {beam.n_elements} with n_half_layers = {beam.n_half_layers}: the finite-difference "
            f"grid's state would take {state_bytes / 2**30:.3g} GiB (limit {MEMORY_LIMIT_BYTES / 2**30:g} GiB); "
            "use fewer elements or layers (the defaults, 200 and 10, resolve a beam impact)")


@functools.lru_cache(maxsize=64)
def beam_grid(beam) -> Grid:
    """The :class:`Grid` of an FDBeam (cached; a grid too large for memory is refused first)."""
    require_grid_fits(beam)
    n_el = beam.n_elements
    n = n_el + 1
    dx = beam.grid_spacing
    left, right = beam.supports
    constrained = np.zeros(n, dtype=bool)
    constrained[0] = left in ("ss", "cc")
    constrained[-1] = right in ("ss", "cc")
    mass_weight = np.ones(n)
    mass_weight[[0, -1]] = 0.5
    section_weight = np.ones(n)
    stencil = np.zeros((3, n))
    stencil[0, 1:-1] = 1.0
    stencil[1, 1:-1] = -2.0
    stencil[2, 1:-1] = 1.0
    for index, end, inward in ((0, left, 2), (n - 1, right, 0)):
        if end == "cc":  # symmetric ghost: κ = 2(w_inner − w_end)/Δx², half tributary length
            section_weight[index] = 0.5
            stencil[1, index] = -2.0
            stencil[inward, index] = 2.0
        else:  # "ss" and "free": M = 0 at the end node
            section_weight[index] = 0.0
    rho_a = beam.mass_per_length
    rho_i = beam.rotary_inertia_per_length
    intervals = np.full(n, 2.0)
    intervals[[0, -1]] = 1.0
    mass_diag = rho_a * dx * mass_weight + rho_i / dx * intervals
    mass_off = np.full(n - 1, -rho_i / dx)
    damping_diag = beam.damping_per_length * dx * mass_weight

    # banded elastic stiffness K = Σ_j D_j b_j b_jᵀ, D_j = c_j Δx EI, b_j the curvature stencil
    weight = section_weight * dx * beam.bending_stiffness
    left_c, centre_c, right_c = stencil / dx**2
    band = np.zeros((3, n))  # upper form: band[2] diagonal, band[1, m] = K[m-1, m], band[0, m] = K[m-2, m]
    band[2] += weight * centre_c**2
    band[2, :-1] += (weight * left_c**2)[1:]
    band[2, 1:] += (weight * right_c**2)[:-1]
    band[1, 1:] += (weight * left_c * centre_c)[1:]  # pair (j−1, j)
    band[1, 1:] += (weight * centre_c * right_c)[:-1]  # pair (j, j+1)
    band[0, 2:] += (weight * left_c * right_c)[1:-1]  # pair (j−1, j+1)
    return Grid(n, dx, constrained, mass_weight, section_weight, stencil, mass_diag, mass_off,
                 damping_diag, grid_frequency_bound(beam), band)


def factorise(grid: Grid, time_step: float):
    """LDLᵀ of A = M_mass + ½Δt C_d with the constrained rows/columns replaced by identity."""
    diag = grid.mass_diag + 0.5 * time_step * grid.damping_diag
    off = grid.mass_off.copy()
    diag = np.where(grid.constrained, 1.0, diag)
    off[grid.constrained[:-1] | grid.constrained[1:]] = 0.0
    pivots = np.empty_like(diag)
    lower = np.zeros_like(diag)  # lower[i] multiplies row i-1
    pivots[0] = diag[0]
    for i in range(1, diag.size):
        lower[i] = off[i - 1] / pivots[i - 1]
        pivots[i] = diag[i] - lower[i] * off[i - 1]
    return pivots, lower


def inverse_mass_at(grid: Grid, node: int) -> float:
    """(M_mass⁻¹)_kk [1/kg] on the free nodes: the node's effective inverse mass."""
    pivots, lower = factorise(grid, 0.0)
    unit = np.zeros(grid.n_nodes)
    unit[node] = 1.0
    return float(tridiagonal_solve(pivots, lower, unit)[node])


def tridiagonal_solve(pivots, lower, rhs):
    """Solve ``A x = rhs`` with the LDLᵀ factors of :func:`factorise`."""
    y = rhs.astype(float).copy()
    for j in range(1, y.size):
        y[j] -= lower[j] * y[j - 1]
    x = np.empty_like(y)
    x[-1] = y[-1] / pivots[-1]
    for j in range(y.size - 2, -1, -1):
        x[j] = y[j] / pivots[j] - lower[j + 1] * x[j + 1]
    return x


def node_for(beam, grid: Grid, position, name):
    """(x0, node): the load point [m] (default mid-span) and its nearest node.

    ``ValueError`` naming ``name`` unless x0 lies in (Δx/2, L − Δx/2) next to supported ends.
    """
    x0 = 0.5 * beam.length if position is None else position
    dx = grid.dx
    low = 0.5 * dx if grid.constrained[0] else 0.0
    high = beam.length - 0.5 * dx if grid.constrained[-1] else beam.length
    require_in_range(name, x0, low, high, low_inclusive=not grid.constrained[0],
                     high_inclusive=not grid.constrained[-1], unit="m")
    node = int(np.clip(round(float(x0) / dx), 0, beam.n_elements))
    return float(x0), node


def gauge_weights(beam, gauge_positions):
    """(positions, left node, weight of the right node) of linear interpolation at gauges."""
    positions = tuple(float(x) for x in np.atleast_1d(np.asarray(gauge_positions, float)))
    for x in positions:
        require_in_range("gauge_positions", x, 0.0, beam.length, unit="m")
    scaled = np.asarray(positions, float) / beam.grid_spacing
    left = np.minimum(np.floor(scaled).astype(np.int64), beam.n_elements - 1)
    weight = scaled - left
    return positions, np.ascontiguousarray(left), np.ascontiguousarray(weight)


def gauge_columns(records, height, n_records) -> dict:
    """History columns of the gauges: ``gauge{g}_deflection_m`` and ``gauge{g}_strain`` (far face, tension +)."""
    cols = {}
    for g in range(records.gauge_w.shape[1]):
        cols[f"gauge{g}_deflection_m"] = records.gauge_w[:n_records, g]
        cols[f"gauge{g}_strain"] = -0.5 * height * records.gauge_k[:n_records, g]
    return cols
