"""General Rayleigh–Ritz modal basis of rectangular plates: Mindlin or Kirchhoff, any S/C/F
edges, full bending stiffness (D11, D22, D12, D66, D16, D26) and transverse shear
(A44, A55, A45).

Each field carries its own edge condition (docs/plates_any_edges.rst, spec §3.7). Every
field is a product of the orthonormal boundary-characteristic Legendre polynomials of
:mod:`impactmaps.targets.ritz`, ``Σ c_il X_i(x/a) Y_l(y/b)``, with the edge-factor
exponent chosen per field and per edge:

============  =========  =================  =================
field         F          S                  C
============  =========  =================  =================
w (Mindlin)   0          1                  1
ψx            0          0 on x = const,    1
                         1 on y = const
ψy            0          1 on x = const,    1
                         0 on y = const
w (Kirchhoff) 0          1                  2
============  =========  =================  =================

(S is the "hard" simple support of the Navier solution: w = 0 and the rotation along the
edge zero.) Each polynomial space contains the previous one, so every frequency falls
monotonically as the basis grows. The Kirchhoff plate is in this space with two functions
fewer per direction (ψ = −∇w is admissible), so the Mindlin basis does not lock as
a/h grows. The energies are those of spec §3.7 with k the shear correction; every Gram
integral is exact (Gauss–Legendre with n + 8 nodes).

Unsymmetric laminates (B ≠ 0) are not modelled here; :class:`~impactmaps.targets.plate.Plate`
refuses them (it has no membrane fields).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from . import ritz

__all__ = ["GeneralPlateSolution", "field_exponents", "solve_general_plate", "general_static_compliance",
           "disc_quadrature", "RESOLUTION_FACTOR", "RESOLUTION_MARGIN", "MIN_FUNCTIONS", "MAX_FUNCTIONS"]

#: Functions per direction per half-wave of the highest resolved mode (measured, docs).
RESOLUTION_FACTOR = 2.0
#: Extra functions per direction on top of ``RESOLUTION_FACTOR · m``.
RESOLUTION_MARGIN = 6
#: Smallest basis per direction.
MIN_FUNCTIONS = 10
#: Largest basis per direction for the Mindlin basis (3 n² unknowns: 3468 at 34).
MAX_FUNCTIONS = 34


def field_exponents(theory: str, edges: str) -> tuple:
    """Edge-factor exponents ((ex0, ex1), (ey0, ey1)) of each field, w first (table above)."""
    def pick(table_x, table_y):
        return ((table_x[edges[0]], table_x[edges[2]]), (table_y[edges[1]], table_y[edges[3]]))

    if theory == "kirchhoff":
        return (pick(ritz.EDGE_CODES, ritz.EDGE_CODES),)
    w = {"F": 0, "S": 1, "C": 1}
    normal = {"F": 0, "S": 0, "C": 1}  # rotation about the edge: free on S
    tangential = {"F": 0, "S": 1, "C": 1}  # rotation along the edge: zero on S
    return (pick(w, w), pick(normal, tangential), pick(tangential, normal))


def _values(xi, n, e0, e1):
    """Orthonormal polynomials of exponents (e0, e1) and two derivatives at ξ, shape (len, n)."""
    transform = ritz._orthonormalising_transform(int(n), int(e0), int(e1))
    raw = ritz._raw_polynomials(np.atleast_1d(np.asarray(xi, dtype=float)), int(n), int(e0), int(e1))
    return tuple(r @ transform for r in raw)


@functools.lru_cache(maxsize=256)
def _gram(n, exponents_a, exponents_b, order_a, order_b):
    """∫0^1 φ_a,i^(order_a) φ_b,k^(order_b) dξ, shape (n, n) (exact)."""
    nodes, weights = legendre.leggauss(n + 8)
    xi = 0.5 * (nodes + 1.0)
    va = _values(xi, n, *exponents_a)[order_a]
    vb = _values(xi, n, *exponents_b)[order_b]
    gram = va.T @ (0.5 * weights[:, None] * vb)
    gram.setflags(write=False)
    return gram


def _strains(theory):
    """Generalised strains as lists of (coefficient, field, ∂x order, ∂y order), and their
    stiffness-matrix index: bending κ (3) then shear γxz, γyz (Mindlin)."""
    if theory == "kirchhoff":
        return [[(-1.0, 0, 2, 0)], [(-1.0, 0, 0, 2)], [(-2.0, 0, 1, 1)]]
    return [[(1.0, 1, 1, 0)], [(1.0, 2, 0, 1)], [(1.0, 1, 0, 1), (1.0, 2, 1, 0)],
            [(1.0, 1, 0, 0), (1.0, 0, 1, 0)], [(1.0, 2, 0, 0), (1.0, 0, 0, 1)]]


def _material_matrix(theory, D, shear):
    """D (3×3) or blockdiag(D, k·[[A55, A45], [A45, A44]]) [N·m, N/m]."""
    if theory == "kirchhoff":
        return np.asarray(D, dtype=float)
    matrix = np.zeros((5, 5))
    matrix[:3, :3] = D
    matrix[3:, 3:] = shear
    return matrix


def selection(theory, n_x, n_y, classes=None) -> tuple:
    """Flat indices (i n_y + l) of the product functions kept, per field.

    ``classes``: the parities (p, q) of w in x and y (0 even, 1 odd about the plate's
    centre lines) to keep, or None for all. With the same edge on opposite sides the
    polynomials X_i have the parity of i, so the modes split into symmetry classes; the
    rotations have the parity of the matching derivative of w (ψx: 1 − p in x).
    """
    i, l = np.divmod(np.arange(n_x * n_y), n_y)
    if classes is None:
        everything = np.arange(n_x * n_y)
        return (everything,) * (1 if theory == "kirchhoff" else 3)
    classes = set(classes)

    def keep(px, py):
        return np.flatnonzero([(int(a), int(b)) in classes for a, b in zip(px, py)])

    w = keep(i % 2, l % 2)
    if theory == "kirchhoff":
        return (w,)
    return (w, keep(1 - i % 2, l % 2), keep(i % 2, 1 - l % 2))


def stiffness_matrix(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes=None) -> np.ndarray:
    """Stiffness matrix [N/m] in the field-blocked orthonormal product basis (w, ψx, ψy),
    restricted to the symmetry ``classes`` (:func:`selection`)."""
    a, b = float(length_x), float(length_y)
    exponents = field_exponents(theory, edges)
    kept = selection(theory, n_x, n_y, classes)
    offsets = np.concatenate([[0], np.cumsum([k.size for k in kept])])
    strains = _strains(theory)
    material = _material_matrix(theory, D, shear)
    stiffness = np.zeros((offsets[-1], offsets[-1]))
    for s, strain_s in enumerate(strains):
        for t, strain_t in enumerate(strains):
            c = material[s, t]
            if c == 0.0:
                continue
            for cs, fs, pxs, pys in strain_s:
                for ct, ft, pxt, pyt in strain_t:
                    gx = _gram(n_x, exponents[fs][0], exponents[ft][0], pxs, pxt)
                    gy = _gram(n_y, exponents[fs][1], exponents[ft][1], pys, pyt)
                    scale = c * cs * ct * a ** (1 - pxs - pxt) * b ** (1 - pys - pyt)
                    ix_s, iy_s = np.divmod(kept[fs], n_y)
                    ix_t, iy_t = np.divmod(kept[ft], n_y)
                    block = gx[ix_s[:, None], ix_t[None, :]] * gy[iy_s[:, None], iy_t[None, :]]
                    stiffness[offsets[fs]:offsets[fs + 1], offsets[ft]:offsets[ft + 1]] += scale * block
    return 0.5 * (stiffness + stiffness.T)


def _mass_diagonal(length_x, length_y, theory, mass_per_area, rotary_inertia, kept):
    area = float(length_x) * float(length_y)
    parts = [np.full(kept[0].size, mass_per_area * area)]
    if theory != "kirchhoff":
        parts += [np.full(k.size, rotary_inertia * area) for k in kept[1:]]
    return np.concatenate(parts)


@dataclass(frozen=True)
class GeneralPlateSolution:
    """Ritz modes of a plate below the basis's resolved frequency.

    Attributes
    ----------
    length_x, length_y : float
        Sides a, b [m].
    theory, edges : str
        Plate theory and edge code (x = 0, y = 0, x = a, y = b).
    n_x, n_y : int
        Functions per direction and per field.
    frequencies : ndarray
        ω_j [rad/s], ascending, every Ritz mode with ω_j ≤ ``computed_up_to``.
    coefficients : ndarray, shape (fields · n_x n_y, modes)
        Mass-normalised eigenvectors (``∫ ρh w² + I2 (ψx² + ψy²) dA = 1``).
    resolved_frequency : float
        Modes up to this frequency [rad/s] are resolved (module rule).
    computed_up_to : float
        Highest eigenvalue requested [rad/s].
    """

    length_x: float
    length_y: float
    theory: str
    edges: str
    n_x: int
    n_y: int
    frequencies: np.ndarray
    coefficients: np.ndarray
    resolved_frequency: float
    computed_up_to: float
    classes: tuple | None = None

    def deflection_basis(self, points) -> np.ndarray:
        """w basis functions at ``points`` (n_points, 2) [m] → (n_points, kept w functions)."""
        points = np.atleast_2d(np.asarray(points, dtype=float))
        (ex, ey) = field_exponents(self.theory, self.edges)[0]
        xv = _values(points[:, 0] / self.length_x, self.n_x, *ex)[0]
        yv = _values(points[:, 1] / self.length_y, self.n_y, *ey)[0]
        full = (xv[:, :, None] * yv[:, None, :]).reshape(points.shape[0], -1)
        return full[:, selection(self.theory, self.n_x, self.n_y, self.classes)[0]]

    def mode_shapes(self, points, count=None) -> np.ndarray:
        """Mass-normalised deflections w_j at ``points`` [kg^-1/2], shape (n_points, count)."""
        count = self.frequencies.size if count is None else int(count)
        basis = self.deflection_basis(points)
        return basis @ self.coefficients[:basis.shape[1], :count]


def _standard_problem(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia, n_x, n_y,
                      classes=None):
    stiffness = stiffness_matrix(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
    mass = _mass_diagonal(length_x, length_y, theory, mass_per_area, rotary_inertia,
                          selection(theory, n_x, n_y, classes))
    scale = 1.0 / np.sqrt(mass)
    return stiffness * scale[:, None] * scale[None, :], scale


@functools.lru_cache(maxsize=8)
def solve_general_plate(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia,
                        n_x, n_y, resolved_frequency, computed_up_to, classes=None) -> GeneralPlateSolution:
    """Ritz eigen-solution (cached by its inputs; pure: same inputs, same bits).

    Parameters
    ----------
    length_x, length_y : float
        Sides a, b [m].
    theory : {"kirchhoff", "mindlin"}
    edges : str
        Edge code.
    D : tuple of tuple
        3×3 bending stiffness [[D11, D12, D16], [D12, D22, D26], [D16, D26, D66]] [N·m].
    shear : tuple of tuple
        2×2 ``k [[A55, A45], [A45, A44]]`` [N/m] (ignored by Kirchhoff).
    mass_per_area, rotary_inertia : float
        ρh [kg/m²] and ρh³/12 [kg].
    n_x, n_y : int
        Functions per direction.
    resolved_frequency, computed_up_to : float
        The basis's resolved frequency and the highest ω computed [rad/s].
    classes : tuple of (int, int), optional
        Symmetry classes kept (:func:`selection`); None for all.
    """
    import scipy.linalg

    matrix, scale = _standard_problem(length_x, length_y, theory, edges, np.array(D), np.array(shear),
                                      mass_per_area, rotary_inertia, n_x, n_y, classes)
    upper = float(computed_up_to) ** 2
    eigenvalues, vectors = scipy.linalg.eigh(matrix, subset_by_value=(-np.inf, upper), driver="evr")
    if eigenvalues.size == 0:
        eigenvalues, vectors = scipy.linalg.eigh(matrix, subset_by_index=(0, 0), driver="evr")
    if eigenvalues[0] <= 0:
        raise RuntimeError(f"Ritz plate stiffness is not positive definite (lowest eigenvalue "
                           f"{eigenvalues[0]:.3e}); the edges leave rigid-body motion")
    vectors = vectors * scale[:, None]
    frequencies = np.sqrt(eigenvalues)
    for array in (frequencies, vectors):
        array.setflags(write=False)
    return GeneralPlateSolution(float(length_x), float(length_y), theory, edges, int(n_x), int(n_y),
                                frequencies, vectors, float(resolved_frequency), float(computed_up_to), classes)


@functools.lru_cache(maxsize=8)
def _stiffness_factor(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes):
    """Cholesky factor of the stiffness matrix (cached: one per plate and basis)."""
    import scipy.linalg

    stiffness = stiffness_matrix(length_x, length_y, theory, edges, np.array(D), np.array(shear), n_x, n_y, classes)
    return scipy.linalg.cho_factor(stiffness), stiffness.shape[0]


def general_static_compliance(length_x, length_y, theory, edges, D, shear, n_x, n_y, load, classes=None) -> float:
    """``fᵀ K⁻¹ f`` [m/N]: static compliance in the basis for the generalised load ``f`` of
    the w block (``load``; the other fields unloaded). The factor of K is cached."""
    import scipy.linalg

    factor, size = _stiffness_factor(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
    f = np.zeros(size)
    f[:load.size] = load
    return float(f @ scipy.linalg.cho_solve(factor, f))


@functools.lru_cache(maxsize=32)
def disc_quadrature(radius: float, pressure: str = "hertz", radial_nodes: int = 16, angular_nodes: int = 32):
    """Offsets (n, 2) [m] and weights (n,) (sum 1) averaging over a disc with the Hertz
    pressure ``∝ sqrt(1 − r²/a²)`` (``s = sin t`` makes the integrand smooth; periodic
    trapezoid in angle)."""
    nodes, weights = legendre.leggauss(radial_nodes)
    t = 0.25 * math.pi * (nodes + 1.0)
    wt = 0.25 * math.pi * weights
    s = np.sin(t)
    if pressure == "hertz":
        radial_weight = wt * s * np.cos(t) ** 2  # s sqrt(1−s²) ds, ds = cos t dt
    else:
        radial_weight = wt * s * np.cos(t)
    theta = 2.0 * math.pi * np.arange(angular_nodes) / angular_nodes
    offsets = radius * np.stack([np.outer(s, np.cos(theta)).ravel(), np.outer(s, np.sin(theta)).ravel()], axis=1)
    w = np.repeat(radial_weight, angular_nodes)
    w = w / w.sum()
    offsets.setflags(write=False)
    w.setflags(write=False)
    return offsets, w


# ---------------------------------------------------------------------------------
# A Plate's general basis: size, modes, contact patch, static compliance
# ---------------------------------------------------------------------------------
def uses_general_basis(plate) -> bool:
    """True when the plate needs this module: Mindlin with edges other than SSSS, or any
    plate with bending–twisting (D16, D26) or A45 coupling (Navier is exact only for
    specially orthotropic SSSS; Kirchhoff specially orthotropic plates on other edges use
    :mod:`impactmaps.targets.ritz`)."""
    coupled = plate.D16 != 0.0 or plate.D26 != 0.0 or plate.A45 != 0.0
    return coupled or (plate.theory == "mindlin" and plate.edges != "SSSS")


def _inputs(plate, edges=None, coupled=True):
    """Hashable arguments of :func:`solve_general_plate` describing ``plate``."""
    d16, d26 = (plate.D16, plate.D26) if coupled else (0.0, 0.0)
    a45 = plate.A45 if coupled else 0.0
    D = ((plate.D11, plate.D12, d16), (plate.D12, plate.D22, d26), (d16, d26, plate.D66))
    k = plate.shear_correction
    shear = ((k * plate.A55, k * a45), (k * a45, k * plate.A44))
    return (plate.length_x, plate.length_y, plate.theory, edges or plate.edges, D, shear,
            plate.mass_per_area, plate.rotary_inertia_per_area)


#: Functions per direction added to the modal basis for the static patch compliance.
STATIC_EXTRA_FUNCTIONS = 8
#: Largest eigenproblem per field set, in unknowns (Mindlin 3 × 34²; dense, seconds).
MAX_UNKNOWNS = 3 * MAX_FUNCTIONS**2


def is_symmetric(plate) -> bool:
    """True when the plate is symmetric about both centre lines (same edge on opposite
    sides) and struck at the centre: its modes split into symmetry classes."""
    x0, y0 = plate.impact_point
    centred = (abs(x0 - 0.5 * plate.length_x) <= 1e-12 * plate.length_x
               and abs(y0 - 0.5 * plate.length_y) <= 1e-12 * plate.length_y)
    return centred and plate.edges[0] == plate.edges[2] and plate.edges[1] == plate.edges[3]


def class_groups(plate) -> list:
    """The symmetry classes that do not couple, as groups (all modes = their union); the
    first holds the modes a centre impact excites. D16, D26 and A45 couple (p, q) with
    (1 − p, 1 − q) (the plate keeps its symmetry under a half turn only)."""
    if not is_symmetric(plate):
        return [None]
    if plate.D16 != 0.0 or plate.D26 != 0.0 or plate.A45 != 0.0:
        return [((0, 0), (1, 1)), ((0, 1), (1, 0))]
    return [((0, 0),), ((0, 1),), ((1, 0),), ((1, 1),)]


def max_functions(theory: str, classes=None) -> int:
    """Largest basis per direction: Mindlin — the eigenproblem of the kept classes holds at
    most :data:`MAX_UNKNOWNS` unknowns; Kirchhoff — :data:`impactmaps.targets.ritz.MAX_FUNCTIONS`."""
    if theory == "kirchhoff":  # as the Kirchhoff Ritz plates (and the static basis of λ)
        return ritz.MAX_FUNCTIONS
    fields, cap = 3, MAX_UNKNOWNS
    fraction = 1.0 if classes is None else len(classes) / 4.0
    return 2 * int(math.sqrt(cap / (fields * fraction)) / 2)


def resolved_frequency(plate, n_x: int, n_y: int) -> float:
    """Highest frequency [rad/s] an ``n_x × n_y`` basis resolves: the simply supported
    frequency (same theory, couplings left out) of the mode with
    ``(n − RESOLUTION_MARGIN)/RESOLUTION_FACTOR`` half-waves in the poorer direction."""
    if plate.theory == "kirchhoff":
        return ritz._resolved_frequency(n_x, n_y, plate.length_x, plate.length_y, plate.D11, plate.D22,
                                        plate.D12, plate.D66, plate.mass_per_area)
    from .plate_navier import mindlin_flexural

    m_x = max((n_x - RESOLUTION_MARGIN) / RESOLUTION_FACTOR, 1.0)
    m_y = max((n_y - RESOLUTION_MARGIN) / RESOLUTION_FACTOR, 1.0)
    omega, _ = mindlin_flexural(plate, np.array([m_x, 1.0]), np.array([1.0, m_y]))
    return float(np.min(omega))


def basis_size(plate, max_frequency: float, classes=None) -> tuple[int, int, bool]:
    """(n_x, n_y, enough): the smallest square basis resolving ``max_frequency`` [rad/s],
    clipped to :func:`max_functions`; ``enough`` is False when even the largest does not."""
    cap = max_functions(plate.theory, classes)
    n = MIN_FUNCTIONS if plate.theory == "mindlin" else ritz.MIN_FUNCTIONS
    while n < cap and resolved_frequency(plate, n, n) < max_frequency:
        n += 2
    n = min(n, cap)
    return n, n, resolved_frequency(plate, n, n) >= max_frequency


def solution(plate, n: int, classes=None) -> GeneralPlateSolution:
    """The cached general solution of ``plate`` with ``n × n`` functions (the kept classes)."""
    top = resolved_frequency(plate, n, n)
    return solve_general_plate(*_inputs(plate), n, n, top, top, classes)


def grown_solution(plate, max_frequency: float, min_modes: int, classes="impact") -> GeneralPlateSolution:
    """Smallest basis resolving ``max_frequency`` [rad/s] and at least ``min_modes`` modes
    (or the largest basis), in the classes a centre impact excites by default."""
    if classes == "impact":
        classes = class_groups(plate)[0]
    n, _, _ = basis_size(plate, max_frequency, classes)
    cap = max_functions(plate.theory, classes)
    while True:
        result = solution(plate, n, classes)
        if result.frequencies.size >= min_modes or n >= cap:
            return result
        n = min(n + 4, cap)


def all_modes(plate, count: int) -> tuple:
    """(ω [rad/s] of the lowest ``count`` resolved modes of every class, sorted; the
    solutions used): one basis size for all classes, grown until ``count`` modes are
    resolved or the largest basis is reached (then fewer may be returned)."""
    groups = class_groups(plate)
    cap = min(max_functions(plate.theory, classes) for classes in groups)
    n = MIN_FUNCTIONS if plate.theory == "mindlin" else ritz.MIN_FUNCTIONS
    while True:
        results = [solution(plate, n, classes) for classes in groups]
        omega = np.sort(np.concatenate([r.frequencies[r.frequencies <= r.resolved_frequency] for r in results]))
        if omega.size >= count or n >= cap:
            return omega[:count], results
        n = min(n + 4, cap)


def patch_weights(result: GeneralPlateSolution, point, contact_radius: float, count: int) -> np.ndarray:
    """Participation [kg^-1/2] of the first ``count`` modes under a Hertz pressure disc of
    ``contact_radius`` [m] centred at ``point`` (the pressure-weighted mean of each mode
    shape; the point value when the radius is 0)."""
    if contact_radius <= 0.0:
        return result.mode_shapes(np.array([point]), count)[0]
    offsets, weights = disc_quadrature(float(contact_radius))
    return weights @ result.mode_shapes(np.asarray(point)[None, :] + offsets, count)


def _patch_load(result: GeneralPlateSolution, point, contact_radius: float) -> np.ndarray:
    if contact_radius <= 0.0:
        return result.deflection_basis(np.array([point]))[0]
    offsets, weights = disc_quadrature(float(contact_radius))
    return weights @ result.deflection_basis(np.asarray(point)[None, :] + offsets)


@functools.lru_cache(maxsize=32)
def patch_static_compliance(plate, n: int, contact_radius: float, classes=None) -> float:
    """Static compliance [m/N] of ``plate`` under the Hertz patch (Mindlin: shear included),
    ``C_basis(edges) + [C_Navier(SSSS) − C_basis(SSSS)]`` with the couplings left out of the
    bracket: the part the polynomial basis misses is local to the load and does not depend
    on the edges (as :meth:`Plate.static_compliance`). Solved in a basis
    :data:`STATIC_EXTRA_FUNCTIONS` larger than the modal one ``n`` (it contains it, so the
    residual is never negative); the factors are cached per plate. Measured (clamped
    quasi-isotropic laminate of the worked example, patch radius 0.5 and 2 mm): n = 12
    is within 3e-4 of n = 48, n = 24 within 3e-5."""
    n_static = -(-(int(n) + STATIC_EXTRA_FUNCTIONS) // 8) * 8  # a multiple of 8: few factors per plate
    n = min(n_static, max(int(n), max_functions(plate.theory, classes)))
    from .patch import hertz_transform, mean_square_transform
    from .plate_static import navier_patch_residual

    def load_for(edges):
        stand_in = GeneralPlateSolution(plate.length_x, plate.length_y, plate.theory, edges, n, n,
                                        np.zeros(0), np.zeros((0, 0)), 0.0, 0.0, classes)
        return _patch_load(stand_in, plate.impact_point, contact_radius)

    full = general_static_compliance(*_inputs(plate)[:6], n, n, load_for(plate.edges), classes)
    ssss = _inputs(plate, "SSSS", coupled=False)
    basis_ssss = general_static_compliance(*ssss[:6], n, n, load_for("SSSS"), classes)
    stiffnesses = (plate.D11, plate.D22, plate.D12, plate.D66)
    if plate.theory == "mindlin":
        stiffnesses += (plate.shear_correction * plate.A55, plate.shear_correction * plate.A44)
    exact = navier_patch_residual(plate.length_x, plate.length_y, stiffnesses, plate.impact_point,
                                  contact_radius, hertz_transform, mean_square=mean_square_transform)
    return full + max(exact - basis_ssss, 0.0)


@functools.lru_cache(maxsize=32)
def classical_compliance(plate) -> float:
    """Classical (Kirchhoff) point compliance [m/N] of a plate with D16/D26, any edges:
    ``C_Ritz(edges, full D) + [C_Navier(SSSS) − C_Ritz(SSSS)]`` (D16, D26 left out of the
    bracket), in the largest Kirchhoff basis of the impact classes (it contains every modal
    basis, so the residual compliance is never negative)."""
    from .plate_static import navier_static_compliance

    classes = class_groups(plate)[0]
    n = max_functions("kirchhoff", classes)
    a, b = plate.length_x, plate.length_y
    unit = ((1.0, 0.0), (0.0, 1.0))

    def load_for(edges):
        stand_in = GeneralPlateSolution(a, b, "kirchhoff", edges, n, n, np.zeros(0), np.zeros((0, 0)),
                                        0.0, 0.0, classes)
        return stand_in.deflection_basis(np.array([plate.impact_point]))[0]

    full = general_static_compliance(a, b, "kirchhoff", plate.edges, _inputs(plate)[4], unit, n, n,
                                     load_for(plate.edges), classes)
    orth = (plate.D11, plate.D22, plate.D12, plate.D66)
    navier = navier_static_compliance(a, b, *orth, plate.impact_point)
    basis_ssss = general_static_compliance(a, b, "kirchhoff", "SSSS", _inputs(plate, "SSSS", coupled=False)[4],
                                           unit, n, n, load_for("SSSS"), classes)
    return full + (navier - basis_ssss)


def general_plate_modes(plate, max_frequency: float, min_modes: int, contact_radius: float = 0.0):
    """(:class:`~impactmaps.targets.base.ModalBasis`, mode-shape function, solution) of a plate
    in the general basis: the modes with ω ≤ ``max_frequency`` [rad/s] the basis resolves
    (at least ``min_modes``); residual compliance as documented in :meth:`Plate.modes`.
    """
    from .base import ModalBasis

    result = grown_solution(plate, max_frequency, min_modes)
    limit = min(max_frequency, result.resolved_frequency)
    count = int(np.sum(result.frequencies <= limit))
    count = max(count, min(min_modes, result.frequencies.size))
    omega = np.asarray(result.frequencies[:count])
    participation = patch_weights(result, plate.impact_point, contact_radius, count)
    damping = np.full(omega.shape, float(plate.damping_ratio))
    if contact_radius > 0.0:
        static = patch_static_compliance(plate, result.n_x, float(contact_radius), result.classes)
        residual = max(static - float(np.sum(participation**2 / omega**2)), 0.0)
        basis = ModalBasis(omega, participation, residual, damping)
    elif plate.theory == "kirchhoff":
        basis = ModalBasis.from_modes(omega, participation, plate.static_compliance(), damping)
    else:
        # point load on a Mindlin plate: the static deflection is infinite; the residual is the
        # classical compliance not carried by the retained modes (≥ 0), as for Navier
        residual = max(plate.static_compliance() - float(np.sum(participation**2 / omega**2)), 0.0)
        basis = ModalBasis(omega, participation, residual, damping)

    def shape_function(points):
        return result.mode_shapes(points, count)

    return basis, shape_function, result
