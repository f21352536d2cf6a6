"""General Rayleigh–Ritz modal basis of rectangular plates: Mindlin or Kirchhoff, any S/C/F
edges, full bending stiffness (D11, D22, D12, D66, D16, D26) and transverse shear
(A44, A55, A45).

Each field carries its own edge condition (docs/plates_any_edges.rst, spec §3.7). Every
field is a product of the orthonormal boundary-characteristic Legendre polynomials of
:mod:`impactmaps.targets.plates.ritz`, ``Σ c_il X_i(x/a) Y_l(y/b)``, with the edge-factor
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

What a :class:`~impactmaps.targets.plates.plate.Plate` takes from it (size, classes, patch, static
compliances) is in :mod:`impactmaps.targets.plates.plate_any_edges`. Unsymmetric laminates (B ≠ 0)
are not modelled here; :class:`~impactmaps.targets.plates.plate.Plate`
refuses them (it has no membrane fields).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import legendre

from . import basis_cache, ritz
from ... import _krylov
from ..._blas import single_blas_thread

__all__ = ["GeneralPlateSolution", "deflection_functions", "field_exponents", "selection", "stiffness_matrix", "solve_general_plate",
           "general_static_compliance", "disc_quadrature", "RESOLUTION_FACTOR", "RESOLUTION_MARGIN",
           "MIN_FUNCTIONS", "MAX_FUNCTIONS"]

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


def _deflection_values(xi, n, e0, e1):
    """The values alone of :func:`_values` (the same bits; no derivative evaluated)."""
    xi = np.atleast_1d(np.asarray(xi, dtype=float))
    transform = ritz._orthonormalising_transform(int(n), int(e0), int(e1))
    g0 = ritz._edge_factor(xi, int(e0), int(e1))[0]
    return (g0[:, None] * legendre.legvander(2.0 * xi - 1.0, int(n) - 1)) @ transform


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
        return np.flatnonzero(np.isin(2 * px + py, [2 * a + b for a, b in classes]))

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
    groups = {}  # (field, field) → [(scale, x Gram, y Gram)] of the upper block triangle
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
                    if fs <= ft:  # a term of a lower block is the transpose of one of the upper block
                        groups.setdefault((fs, ft), []).append((scale, gx, gy))
    stiffness = np.zeros((offsets[-1], offsets[-1]))
    for (fs, ft), terms in groups.items():
        block = _kron_sum(terms, kept[fs], kept[ft], n_y)
        rows, columns = slice(offsets[fs], offsets[fs + 1]), slice(offsets[ft], offsets[ft + 1])
        if fs == ft:
            stiffness[rows, columns] = 0.5 * (block + block.T)
        else:
            stiffness[rows, columns] = block
            stiffness[columns, rows] = block.T
    return stiffness


def _kron_sum(terms, kept_s, kept_t, n_y):
    """``Σ scale · gx[i_s, i_t] gy[l_s, l_t]`` over ``terms`` [(scale, gx, gy)] on the kept rows
    and columns: one matrix product per pair of parity parts (:func:`_parity_parts`; a product set
    is one part) instead of a Kronecker product per term, else gathered term by term."""
    row_parts, column_parts = _parity_parts(kept_s, n_y), _parity_parts(kept_t, n_y)
    if row_parts is None or column_parts is None:
        return sum(scale * _gathered_block(gx, gy, kept_s, kept_t, n_y) for scale, gx, gy in terms)
    block = np.empty((kept_s.size, kept_t.size))
    for where_s, xs, ys in row_parts:
        for where_t, xt, yt in column_parts:
            x = np.stack([scale * gx[np.ix_(xs, xt)] for scale, gx, _ in terms]).reshape(len(terms), -1)
            y = np.stack([gy[np.ix_(ys, yt)] for _, _, gy in terms]).reshape(len(terms), -1)
            part = (x.T @ y).reshape(xs.size, xt.size, ys.size, yt.size).transpose(0, 2, 1, 3)
            part = part.reshape(xs.size * ys.size, xt.size * yt.size)
            if len(row_parts) == 1 and len(column_parts) == 1:
                return np.ascontiguousarray(part)
            block[np.ix_(where_s, where_t)] = part
    return block


def _factors(kept, n_y):
    """(x indices, y indices) of kept flat indices ``i n_y + l`` that are their product set
    (all functions, or one symmetry class), else None."""
    ix, iy = np.divmod(kept, n_y)
    xs, ys = np.unique(ix), np.unique(iy)
    if xs.size * ys.size == kept.size and np.array_equal(kept, (xs[:, None] * n_y + ys[None, :]).ravel()):
        return xs, ys
    return None


def _parity_parts(kept, n_y):
    """Kept flat indices ``i n_y + l`` split by the parities of (i, l): [(their positions in
    ``kept``, x indices, y indices)], when each part is a product set (a union of symmetry
    classes), else None."""
    ix, iy = np.divmod(kept, n_y)
    parts = []
    for p in (0, 1):
        for q in (0, 1):
            where = np.flatnonzero((ix % 2 == p) & (iy % 2 == q))
            factors = _factors(kept[where], n_y) if where.size else ()
            if factors is None:
                return None
            if where.size:
                parts.append((where, *factors))
    return parts


def _gathered_block(gx, gy, kept_s, kept_t, n_y):
    """``gx[i_s, i_t] gy[l_s, l_t]`` over kept rows and columns that are no union of symmetry
    classes (:func:`_kron_sum` builds the others as matrix products), gathered."""
    ix_s, iy_s = np.divmod(kept_s, n_y)
    ix_t, iy_t = np.divmod(kept_t, n_y)
    return gx[ix_s[:, None], ix_t[None, :]] * gy[iy_s[:, None], iy_t[None, :]]


def _mass_diagonal(length_x, length_y, theory, mass_per_area, rotary_inertia, kept):
    area = float(length_x) * float(length_y)
    parts = [np.full(kept[0].size, mass_per_area * area)]
    if theory != "kirchhoff":
        parts += [np.full(k.size, rotary_inertia * area) for k in kept[1:]]
    return np.concatenate(parts)


def deflection_functions(length_x, length_y, theory, w_exponents, n_x, n_y, classes, points) -> np.ndarray:
    """The kept w functions ``X_i(x/a) Y_l(y/b)`` of an ``n_x × n_y`` basis whose w edge exponents are
    ``w_exponents`` ((ex0, ex1), (ey0, ey1), :func:`field_exponents`) at ``points`` (n_points, 2) [m],
    shape (n_points, kept w functions)."""
    points = np.atleast_2d(np.asarray(points, dtype=float))
    (ex, ey) = w_exponents
    xv = _deflection_values(points[:, 0] / length_x, n_x, *ex)
    yv = _deflection_values(points[:, 1] / length_y, n_y, *ey)
    i, l = np.divmod(selection(theory, n_x, n_y, classes)[0], n_y)
    return xv[:, i] * yv[:, l]  # the kept columns of the products X_i Y_l


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
        ω_j [rad/s], ascending, every Ritz mode with ω_j ≤ ``resolved_frequency`` (at least one).
    coefficients : ndarray, shape (fields · n_x n_y, modes)
        Mass-normalised eigenvectors (``∫ ρh w² + I2 (ψx² + ψy²) dA = 1``).
    resolved_frequency : float
        Modes up to this frequency [rad/s] are resolved (:mod:`.plate_any_edges`).
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
    classes: tuple | None = None

    @property
    def n(self) -> int:
        """The basis's size: its functions per field along the direction it resolves worse
        (:func:`impactmaps.targets.plates.plate_any_edges.functions`)."""
        return max(self.n_x, self.n_y)

    def deflection_basis(self, points) -> np.ndarray:
        """w basis functions at ``points`` (n_points, 2) [m] → (n_points, kept w functions)."""
        return deflection_functions(self.length_x, self.length_y, self.theory, field_exponents(self.theory, self.edges)[0],
                                    self.n_x, self.n_y, self.classes, points)

    def mode_shapes(self, points, count=None) -> np.ndarray:
        """Mass-normalised deflections w_j at ``points`` [kg^-1/2], shape (n_points, count)."""
        count = self.frequencies.size if count is None else int(count)
        basis = self.deflection_basis(points)
        return basis @ self.coefficients[:basis.shape[1], :count]


@functools.lru_cache(maxsize=1)
@single_blas_thread
def _last_stiffness(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes):
    """:func:`stiffness_matrix` of hashable inputs (``D``, ``shear`` as tuples), read-only; the
    last one kept, so that the eigenproblem and the static factor of one basis (the same
    inputs, one after the other) assemble it once."""
    stiffness = stiffness_matrix(length_x, length_y, theory, edges, np.array(D), np.array(shear), n_x, n_y, classes)
    stiffness.setflags(write=False)
    return stiffness


def _mass_scale(length_x, length_y, theory, mass_per_area, rotary_inertia, n_x, n_y, classes=None):
    """S = M^(−1/2) of the basis's diagonal mass matrix [kg^(−1/2)]."""
    return 1.0 / np.sqrt(_mass_diagonal(length_x, length_y, theory, mass_per_area, rotary_inertia,
                                        selection(theory, n_x, n_y, classes)))


def _standard_problem(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia, n_x, n_y,
                      classes=None):
    """(S K S, S): the mass-scaled stiffness of the standard eigenproblem and the scale S."""
    stiffness = _last_stiffness(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
    scale = _mass_scale(length_x, length_y, theory, mass_per_area, rotary_inertia, n_x, n_y, classes)
    return stiffness * scale[:, None] * scale[None, :], scale


@functools.lru_cache(maxsize=8)
def solve_general_plate(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia,
                        n_x, n_y, resolved_frequency, classes=None) -> GeneralPlateSolution:
    """Ritz eigen-solution (cached by its inputs in the process and on disk,
    :mod:`~impactmaps.targets.plates.basis_cache`; pure: same inputs, same bits).

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
    resolved_frequency : float
        The basis's resolved frequency [rad/s]: the modes below it are computed.
    classes : tuple of (int, int), optional
        Symmetry classes kept (:func:`selection`); None for all.
    """
    inputs = {"length_x": length_x, "length_y": length_y, "theory": theory, "edges": edges, "D": D, "shear": shear,
              "mass_per_area": mass_per_area, "rotary_inertia": rotary_inertia, "n_x": n_x, "n_y": n_y,
              "resolved_frequency": resolved_frequency, "classes": classes}
    arrays = basis_cache.cached_arrays("general-modes", inputs, lambda: _eigen_solution(
        length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia, n_x, n_y, resolved_frequency,
        classes))
    frequencies, vectors = arrays["frequencies"], arrays["coefficients"]
    return GeneralPlateSolution(float(length_x), float(length_y), theory, edges, int(n_x), int(n_y),
                                frequencies, vectors, float(resolved_frequency), classes)


@single_blas_thread
def _eigen_solution(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia, n_x, n_y,
                    resolved_frequency, classes) -> dict:
    """{"frequencies": ω_j [rad/s], "coefficients": mass-normalised eigenvectors} of
    :func:`solve_general_plate` (the expensive part): dense below
    :data:`~impactmaps._krylov.KRYLOV_MIN_UNKNOWNS` unknowns, else shift-invert block Krylov on the
    stiffness's Cholesky factor (:mod:`impactmaps._krylov`; dense if it does not converge)."""
    import scipy.linalg

    upper = float(resolved_frequency) ** 2
    scale = _mass_scale(length_x, length_y, theory, mass_per_area, rotary_inertia, n_x, n_y, classes)
    found = None
    if scale.size >= _krylov.KRYLOV_MIN_UNKNOWNS:
        try:
            factor, _ = _stiffness_factor(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
        except np.linalg.LinAlgError:  # not positive definite: the dense solution says so
            factor = None
        if factor is not None:
            def apply_inverse(x):  # A = S K S, A⁻¹ x = S⁻¹ K⁻¹ S⁻¹ x
                return scipy.linalg.cho_solve(factor, x / scale[:, None], check_finite=False) / scale[:, None]

            found = _krylov.lowest_by_krylov(apply_inverse, scale.size, upper)
    if found is None:
        matrix, scale = _standard_problem(length_x, length_y, theory, edges, D, shear, mass_per_area, rotary_inertia,
                                          n_x, n_y, classes)
        found = scipy.linalg.eigh(matrix, subset_by_value=(-np.inf, upper), driver="evr")
        if found[0].size == 0:
            found = scipy.linalg.eigh(matrix, subset_by_index=(0, 0), driver="evr")
    eigenvalues, vectors = found
    if eigenvalues[0] <= 0:
        raise RuntimeError(f"Ritz plate stiffness is not positive definite (lowest eigenvalue "
                           f"{eigenvalues[0]:.3e}); the edges leave rigid-body motion")
    return {"frequencies": np.sqrt(eigenvalues), "coefficients": vectors * scale[:, None]}


@functools.lru_cache(maxsize=8)
@single_blas_thread
def _stiffness_factor(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes):
    """Cholesky factor of the stiffness matrix (cached: one per plate and basis)."""
    import scipy.linalg

    stiffness = _last_stiffness(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
    return scipy.linalg.cho_factor(stiffness), stiffness.shape[0]


@single_blas_thread
def general_static_compliance(length_x, length_y, theory, edges, D, shear, n_x, n_y, load, classes=None) -> float:
    """``fᵀ K⁻¹ f`` [m/N]: static compliance in the basis for the generalised load ``f`` of
    the w block (``load``; the other fields unloaded). The factor of K is cached."""
    import scipy.linalg

    factor, size = _stiffness_factor(length_x, length_y, theory, edges, D, shear, n_x, n_y, classes)
    f = np.zeros(size)
    f[:load.size] = load
    return float(f @ scipy.linalg.cho_solve(factor, f, check_finite=False))  # a factor of finite K


@functools.lru_cache(maxsize=32)
def disc_quadrature(radius: float, radial_nodes: int = 16, angular_nodes: int = 32):
    """Offsets (n, 2) [m] and weights (n,) (sum 1) averaging over a disc with the Hertz
    pressure ``∝ sqrt(1 − r²/a²)`` (``s = sin t`` makes the integrand smooth; periodic
    trapezoid in angle)."""
    nodes, weights = legendre.leggauss(radial_nodes)
    t = 0.25 * math.pi * (nodes + 1.0)
    wt = 0.25 * math.pi * weights
    s = np.sin(t)
    radial_weight = wt * s * np.cos(t) ** 2  # s sqrt(1−s²) ds, ds = cos t dt
    theta = 2.0 * math.pi * np.arange(angular_nodes) / angular_nodes
    offsets = radius * np.stack([np.outer(s, np.cos(theta)).ravel(), np.outer(s, np.sin(theta)).ravel()], axis=1)
    w = np.repeat(radial_weight, angular_nodes)
    w = w / w.sum()
    offsets.setflags(write=False)
    w.setflags(write=False)
    return offsets, w
