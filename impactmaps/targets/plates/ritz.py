"""Rayleigh–Ritz modal basis of rectangular Kirchhoff plates with any S/C/F edges.

The transverse deflection is expanded in products of one-dimensional
*boundary-characteristic orthogonal polynomials* (the idea of R. B. Bhat, J. Sound Vib. 102
(1985) 493–499; here built from Legendre polynomials times an edge factor):

    w(x, y) = Σ_i Σ_l c_il X_i(x/a) Y_l(y/b),
    X_i(ξ) = Σ_k T_ki ξ^e0 (1 − ξ)^e1 P_k(2ξ − 1),

where ``P_k`` are Legendre polynomials and the edge factor exponents ``e`` are 0 for a
free edge, 1 for a simply supported edge (w = 0; the zero-moment condition is natural
and emerges from the energy) and 2 for a clamped edge (w = ∂w/∂n = 0). The matrix
``T`` orthonormalises the functions in L²(0, 1) (QR factorisation of the sampled basis at
Gauss–Legendre nodes), so the plate mass matrix is ``ρh a b I`` and the generalised
eigenproblem reduces to a standard symmetric one.

The polynomial space of degree ``n`` contains the one of degree ``n − 1``, so Ritz
frequencies decrease monotonically towards the exact ones as the basis grows, and the
point compliance obtained by a static solve with the Ritz stiffness matrix *increases*
monotonically towards the exact one (both are minimum-energy statements).

Only the specially orthotropic Kirchhoff (shear-rigid, no rotary inertia) plate is solved
here; Mindlin plates on edges other than SSSS and plates with D16, D26 or A45 use the
general basis of :mod:`impactmaps.targets.plates.plate_general` (same polynomials, one set per
field).

Basis-size rule (:func:`ritz_basis_size`): in each direction, take the largest number of
half-waves ``m`` of a simply supported mode ``(m, 1)`` (or ``(1, n)``) with a frequency at
or below ``max_frequency``; use ``n = ceil(RESOLUTION_FACTOR · m) + RESOLUTION_MARGIN``
functions in that direction, clipped to ``[MIN_FUNCTIONS, MAX_FUNCTIONS]``. Conversely a
basis with ``n`` functions is said to *resolve* the modes with at most
``(n − RESOLUTION_MARGIN)/RESOLUTION_FACTOR`` half-waves in that direction; see
:attr:`RitzPlateSolution.resolved_frequency`. Measured accuracy of the modes declared
resolved (square and 1 × 0.737 plates, n = 14 … 40 per direction): SSSS within 2e-8 of
Navier, CCCC within 3e-8 of a 54 × 54 basis; with free edges the corner singularities
slow the polynomial convergence to algebraic, and the error is ≈ 1e-4 at n = 14 falling
to ≈ 1e-5 at n = 40 (CFCF, CFFF), ≈ 1e-6 for SCSF/CSFS.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from ..._checks import require_choice, require_in_range, require_positive
from ..._blas import single_blas_thread

__all__ = [
    "EDGE_CODES",
    "RESOLUTION_FACTOR",
    "RESOLUTION_MARGIN",
    "MIN_FUNCTIONS",
    "MAX_FUNCTIONS",
    "RitzPlateSolution",
    "boundary_polynomials",
    "ritz_basis_size",
    "largest_resolved_frequency",
    "solve_ritz_plate",
    "ritz_static_compliance",
    "has_rigid_body_freedom",
]

#: Edge codes and the exponent of the edge factor ξ^e (free, simply supported, clamped).
EDGE_CODES = {"F": 0, "S": 1, "C": 2}

#: Legendre functions needed per half-wave of the highest resolved mode (see module doc).
RESOLUTION_FACTOR = 2.0
#: Extra functions per direction on top of ``RESOLUTION_FACTOR · m``.
RESOLUTION_MARGIN = 6
#: Smallest basis per direction.
MIN_FUNCTIONS = 14
#: Largest basis per direction (the dense eigenproblem has ``n_x n_y`` unknowns).
MAX_FUNCTIONS = 40


def _edge_factor(xi, e0: int, e1: int):
    """ξ^e0 (1 − ξ)^e1 and its first two derivatives with respect to ξ."""
    poly = np.polynomial.Polynomial([0.0, 1.0]) ** e0 * np.polynomial.Polynomial([1.0, -1.0]) ** e1
    return poly(xi), poly.deriv(1)(xi), poly.deriv(2)(xi)


def _raw_polynomials(xi, n_functions: int, e0: int, e1: int):
    """Edge factor times Legendre P_k(2ξ − 1), k < n, and ξ-derivatives; shape (len(xi), n)."""
    t = 2.0 * np.asarray(xi, dtype=float) - 1.0
    p0 = legendre.legvander(t, n_functions - 1)
    # d/dξ = 2 d/dt
    p1 = 2.0 * legendre.legval(t, _legendre_derivatives(n_functions, 1)).T if n_functions > 1 else np.zeros_like(p0)
    p2 = 4.0 * legendre.legval(t, _legendre_derivatives(n_functions, 2)).T if n_functions > 2 else np.zeros_like(p0)
    g0, g1, g2 = _edge_factor(np.asarray(xi, dtype=float), e0, e1)
    g0, g1, g2 = g0[:, None], g1[:, None], g2[:, None]
    return g0 * p0, g1 * p0 + g0 * p1, g2 * p0 + 2.0 * g1 * p1 + g0 * p2


@functools.lru_cache(maxsize=64)
def _legendre_derivatives(n_functions: int, order: int) -> np.ndarray:
    """Legendre coefficients (rows) of the ``order``-th t-derivative of P_k, k < n, per column
    (cached: NumPy's ``legder`` loops over the degrees in Python)."""
    coefficients = legendre.legder(np.eye(n_functions), order, axis=0)
    coefficients.setflags(write=False)
    return coefficients


@functools.lru_cache(maxsize=64)
def _orthonormalising_transform(n_functions: int, e0: int, e1: int) -> np.ndarray:
    """Matrix T (n × n) making ``raw @ T`` orthonormal in L²(0, 1)."""
    nodes, weights = legendre.leggauss(n_functions + 8)
    xi = 0.5 * (nodes + 1.0)
    raw, _, _ = _raw_polynomials(xi, n_functions, e0, e1)
    _, r = np.linalg.qr(np.sqrt(0.5 * weights)[:, None] * raw)
    transform = np.linalg.inv(r)
    transform.setflags(write=False)
    return transform


def boundary_polynomials(xi, n_functions: int, start_edge: str, end_edge: str):
    """Orthonormal boundary-characteristic polynomials on [0, 1] and their derivatives.

    Parameters
    ----------
    xi : array_like
        Dimensionless coordinates ξ ∈ [0, 1] [-].
    n_functions : int
        Number of functions n (polynomial degrees e0 + e1 … e0 + e1 + n − 1).
    start_edge, end_edge : {"S", "C", "F"}
        Edge condition at ξ = 0 and ξ = 1.

    Returns
    -------
    values, first, second : ndarray, shape (len(xi), n_functions)
        φ_i(ξ), dφ_i/dξ and d²φ_i/dξ² [-]; ``∫0^1 φ_i φ_k dξ = δ_ik``.
    """
    require_choice("start_edge", start_edge, EDGE_CODES)
    require_choice("end_edge", end_edge, EDGE_CODES)
    transform = _orthonormalising_transform(int(n_functions), EDGE_CODES[start_edge], EDGE_CODES[end_edge])
    raw = _raw_polynomials(np.atleast_1d(np.asarray(xi, dtype=float)), int(n_functions),
                           EDGE_CODES[start_edge], EDGE_CODES[end_edge])
    return tuple(r @ transform for r in raw)


def _one_dimensional_matrices(n_functions: int, start_edge: str, end_edge: str):
    """Gram matrices on [0, 1]: ∫φφ (= I), ∫φ'φ', ∫φ''φ'', ∫φ''_i φ_k (exact quadrature)."""
    nodes, weights = legendre.leggauss(n_functions + 8)
    xi = 0.5 * (nodes + 1.0)
    w = 0.5 * weights[:, None]
    v0, v1, v2 = boundary_polynomials(xi, n_functions, start_edge, end_edge)
    m11 = v1.T @ (w * v1)
    m22 = v2.T @ (w * v2)
    m20 = v2.T @ (w * v0)
    return 0.5 * (m11 + m11.T), 0.5 * (m22 + m22.T), m20


def has_rigid_body_freedom(edges: str) -> bool:
    """True when the edge code lets the plate move as a rigid body (no C, at most one S).

    Rigid motions ``w = α + βx + γy`` are stopped by a clamped edge, by two opposite
    simply supported edges, and by two adjacent ones; a single simply supported edge
    leaves a rigid rotation about it and free edges leave everything.
    """
    return "C" not in edges and edges.count("S") <= 1


def require_edges(edges, theory: str) -> None:
    """Raise ``ValueError`` unless ``edges`` is a known 4-character edge code that holds the
    plate against rigid motion (:func:`has_rigid_body_freedom`); any theory.""" 
    if not (isinstance(edges, str) and len(edges) == 4 and all(c in EDGE_CODES for c in edges)):
        raise ValueError(
            f"edges = {edges!r} is not known: valid values are 4-character codes of "
            "'S' (simply supported), 'C' (clamped), 'F' (free) for the edges "
            "(x=0, y=0, x=a, y=b), e.g. 'SSSS', 'CCCC', 'CSCS'"
        )
    if has_rigid_body_freedom(edges):
        raise ValueError(
            f"edges = {edges!r} is not supported: the plate can move as a rigid body "
            "(no clamped edge and at most one simply supported edge); its static point "
            "stiffness is zero"
        )


def _stiffness_matrix(length_x, length_y, D11, D22, D12, D66, edges, n_x, n_y):
    """Kirchhoff bending stiffness matrix [N/m] in the orthonormal product basis."""
    a, b = length_x, length_y
    m11x, m22x, m20x = _one_dimensional_matrices(n_x, edges[0], edges[2])
    m11y, m22y, m20y = _one_dimensional_matrices(n_y, edges[1], edges[3])
    eye_x, eye_y = np.eye(n_x), np.eye(n_y)
    stiffness = (
        D11 * b / a**3 * np.kron(m22x, eye_y)
        + D22 * a / b**3 * np.kron(eye_x, m22y)
        + D12 / (a * b) * (np.kron(m20x, m20y.T) + np.kron(m20x.T, m20y))
        + 4.0 * D66 / (a * b) * np.kron(m11x, m11y)
    )
    return 0.5 * (stiffness + stiffness.T)


@dataclass(frozen=True)
class RitzPlateSolution:
    """Ritz eigen-solution of a Kirchhoff plate (all ``n_x n_y`` Ritz modes).

    Attributes
    ----------
    length_x, length_y : float
        Plate sides a, b [m].
    edges : str
        Edge code at x = 0, y = 0, x = a, y = b.
    n_x, n_y : int
        Number of one-dimensional functions in x and y.
    mass_per_area : float
        ρh [kg/m²].
    frequencies : ndarray, shape (n_x n_y,)
        Ritz natural frequencies ω_j [rad/s], ascending.
    coefficients : ndarray, shape (n_x n_y, n_x n_y)
        Orthonormal eigenvectors (columns) in the product basis, index ``i n_y + l``.
    resolved_frequency : float
        Frequencies up to this value [rad/s] are resolved by the basis (module rule).
    """

    length_x: float
    length_y: float
    edges: str
    n_x: int
    n_y: int
    mass_per_area: float
    frequencies: np.ndarray
    coefficients: np.ndarray
    resolved_frequency: float

    def basis_values(self, points) -> np.ndarray:
        """Product-basis functions X_i(x/a) Y_l(y/b) at ``points`` (shape (n_points, 2)) [-]."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        x_values, _, _ = boundary_polynomials(points[:, 0] / self.length_x, self.n_x, self.edges[0], self.edges[2])
        y_values, _, _ = boundary_polynomials(points[:, 1] / self.length_y, self.n_y, self.edges[1], self.edges[3])
        return (x_values[:, :, None] * y_values[:, None, :]).reshape(points.shape[0], -1)

    def mode_shapes(self, points, mode_count: int | None = None) -> np.ndarray:
        """Mass-normalised mode shapes φ_j at ``points`` [kg^-1/2], shape (n_points, modes).

        Normalisation: ``∫∫ ρh φ_j φ_k dx dy = δ_jk``.
        """
        count = self.frequencies.size if mode_count is None else int(mode_count)
        scale = 1.0 / math.sqrt(self.mass_per_area * self.length_x * self.length_y)
        return scale * (self.basis_values(points) @ self.coefficients[:, :count])


def ritz_basis_size(max_frequency, length_x, length_y, D11, D22, D12, D66, mass_per_area):
    """Number of Ritz functions per direction needed to resolve ``max_frequency``.

    Parameters
    ----------
    max_frequency : float
        Highest natural frequency to resolve [rad/s].
    length_x, length_y, D11, D22, D12, D66, mass_per_area
        As in :func:`solve_ritz_plate`.

    Returns
    -------
    n_x, n_y : int
        Basis size per direction (rule in the module docstring), clipped to
        ``[MIN_FUNCTIONS, MAX_FUNCTIONS]``.
    required_x, required_y : int
        The unclipped sizes (larger than ``MAX_FUNCTIONS`` when the basis cannot resolve
        ``max_frequency``).
    """
    m_x = _max_half_waves(max_frequency, length_x, length_y, D11, D22, D12 + 2.0 * D66, mass_per_area)
    m_y = _max_half_waves(max_frequency, length_y, length_x, D22, D11, D12 + 2.0 * D66, mass_per_area)
    required = [math.ceil(RESOLUTION_FACTOR * m) + RESOLUTION_MARGIN for m in (m_x, m_y)]
    clipped = [min(max(r, MIN_FUNCTIONS), MAX_FUNCTIONS) for r in required]
    return clipped[0], clipped[1], required[0], required[1]


def _max_half_waves(frequency, length, other_length, D_along, D_across, H, mass_per_area) -> float:
    """Largest m (real) with the SS Kirchhoff frequency of mode (m, 1) ≤ ``frequency``."""
    # D_along k⁴ + 2H k² q² + D_across q⁴ = ρh ω², k = mπ/L, q = π/L_other
    q2 = (math.pi / other_length) ** 2
    c = mass_per_area * frequency**2 - D_across * q2**2
    if c <= 0:
        return 0.0
    k2 = (-H * q2 + math.sqrt((H * q2) ** 2 + D_along * c)) / D_along
    return math.sqrt(max(k2, 0.0)) * length / math.pi


def _resolved_frequency(n_x, n_y, length_x, length_y, D11, D22, D12, D66, mass_per_area) -> float:
    """SS Kirchhoff frequency of the highest mode resolved by an n_x × n_y basis [rad/s]."""
    return min(_direction_frequencies(n_x, n_y, length_x, length_y, D11, D22, D12, D66, mass_per_area))


def _direction_frequencies(n_x, n_y, length_x, length_y, D11, D22, D12, D66, mass_per_area) -> tuple:
    """(along x, along y) [rad/s]: the SS Kirchhoff frequency of the mode with
    ``(n − RESOLUTION_MARGIN)/RESOLUTION_FACTOR`` half-waves along each direction (one across)."""
    H = D12 + 2.0 * D66
    result = []
    for n, D_along, D_across, length, other in (
        (n_x, D11, D22, length_x, length_y),
        (n_y, D22, D11, length_y, length_x),
    ):
        m = (n - RESOLUTION_MARGIN) / RESOLUTION_FACTOR
        k2 = (m * math.pi / length) ** 2
        q2 = (math.pi / other) ** 2
        result.append(math.sqrt((D_along * k2**2 + 2.0 * H * k2 * q2 + D_across * q2**2) / mass_per_area))
    return tuple(result)


def largest_resolved_frequency(length_x, length_y, D11, D22, D12, D66, mass_per_area) -> float:
    """Highest frequency [rad/s] the largest basis (:data:`MAX_FUNCTIONS` per direction)
    resolves (module rule); arguments as :func:`ritz_basis_size`."""
    return _resolved_frequency(MAX_FUNCTIONS, MAX_FUNCTIONS, length_x, length_y, D11, D22, D12, D66,
                               mass_per_area)


def _validate(length_x, length_y, D11, D22, D12, D66, mass_per_area, edges, n_x, n_y):
    require_positive("length_x", length_x, "m")
    require_positive("length_y", length_y, "m")
    for name, value in (("D11", D11), ("D22", D22), ("D66", D66)):
        require_positive(name, value, "N·m")
    require_positive("mass_per_area", mass_per_area, "kg/m²")
    if not (isinstance(edges, str) and len(edges) == 4 and all(c in EDGE_CODES for c in edges)):
        raise ValueError(
            f"edges = {edges!r} is not known: valid values are 4-character codes of "
            "'S', 'C', 'F' in the order (x=0, y=0, x=a, y=b), e.g. 'SSSS', 'CCCC', 'CSCS'"
        )
    if has_rigid_body_freedom(edges):
        raise ValueError(
            f"edges = {edges!r} is not supported: the plate can move as a rigid body "
            "(no clamped edge and at most one simply supported edge), so its static point "
            "compliance is infinite"
        )
    require_in_range("n_x", n_x, 2, 400)
    require_in_range("n_y", n_y, 2, 400)


@functools.lru_cache(maxsize=4)
@single_blas_thread
def solve_ritz_plate(length_x, length_y, D11, D22, D12, D66, mass_per_area, edges, n_x, n_y) -> RitzPlateSolution:
    """Solve the Kirchhoff plate eigenproblem in an ``n_x × n_y`` Ritz basis (cached).

    Parameters
    ----------
    length_x, length_y : float
        Plate sides a, b [m].
    D11, D22, D12, D66 : float
        Bending stiffnesses [N·m].
    mass_per_area : float
        ρh [kg/m²].
    edges : str
        Four characters from {"S", "C", "F"} for the edges x = 0, y = 0, x = a, y = b.
    n_x, n_y : int
        Number of one-dimensional functions per direction.

    Returns
    -------
    RitzPlateSolution
        All ``n_x n_y`` Ritz modes. Results are cached (last 4 distinct plates), keyed by
        everything except the impact point.
    """
    _validate(length_x, length_y, D11, D22, D12, D66, mass_per_area, edges, n_x, n_y)
    import scipy.linalg

    stiffness = _stiffness_matrix(length_x, length_y, D11, D22, D12, D66, edges, int(n_x), int(n_y))
    eigenvalues, vectors = scipy.linalg.eigh(stiffness / (mass_per_area * length_x * length_y), driver="evd")
    if eigenvalues[0] <= 0:
        raise RuntimeError(
            f"Ritz stiffness matrix is not positive definite (lowest eigenvalue {eigenvalues[0]:.3e}); "
            "reduce the basis size"
        )
    frequencies = np.sqrt(eigenvalues)
    frequencies.setflags(write=False)
    vectors.setflags(write=False)
    return RitzPlateSolution(
        length_x=float(length_x),
        length_y=float(length_y),
        edges=edges,
        n_x=int(n_x),
        n_y=int(n_y),
        mass_per_area=float(mass_per_area),
        frequencies=frequencies,
        coefficients=vectors,
        resolved_frequency=_resolved_frequency(n_x, n_y, length_x, length_y, D11, D22, D12, D66, mass_per_area),
    )


@single_blas_thread
def ritz_static_compliance(length_x, length_y, D11, D22, D12, D66, edges, point, n_x, n_y) -> float:
    """Point compliance [m/N] at ``point`` from a static solve ``K u = f`` in the Ritz basis.

    This is a lower bound that increases monotonically with the basis size (the point load
    deflection of a Kirchhoff plate has an ``r² ln r`` singularity, so convergence is
    algebraic, roughly as ``1/n²``).

    Parameters
    ----------
    length_x, length_y, D11, D22, D12, D66, edges, n_x, n_y
        As in :func:`solve_ritz_plate`.
    point : tuple of float
        Load and observation point (x0, y0) [m].
    """
    _validate(length_x, length_y, D11, D22, D12, D66, 1.0, edges, n_x, n_y)
    import scipy.linalg

    stiffness = _stiffness_matrix(length_x, length_y, D11, D22, D12, D66, edges, int(n_x), int(n_y))
    x_values, _, _ = boundary_polynomials(point[0] / length_x, n_x, edges[0], edges[2])
    y_values, _, _ = boundary_polynomials(point[1] / length_y, n_y, edges[1], edges[3])
    load = np.kron(x_values[0], y_values[0])
    factor = scipy.linalg.cho_factor(stiffness)
    return float(load @ scipy.linalg.cho_solve(factor, load))
