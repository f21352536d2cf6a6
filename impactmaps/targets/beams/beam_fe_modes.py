"""Rayleigh and Timoshenko beams with any support: p-version finite-element modes
(method, accuracy and cost: docs/physics.rst, Beam targets).
"""

from __future__ import annotations

import math
import warnings
from functools import lru_cache

import numpy as np
import scipy.sparse
from numpy.polynomial import legendre

from ..._checks import require_nonnegative
from .beam_fe_eigen import count_below, eigenpairs_below
from .beam_section import (
    BeamSection,
    ModeSet,
    as_points,
    cutoff_with_min_modes,
    frequency_at_wavenumber,
    largest_wavenumber,
)

__all__ = ["finite_element_modes", "finite_element_mode_count", "finite_element_resolution_limit", "FE_DEGREE", "FE_RESOLUTION", "FE_MAX_DOFS"]

#: Polynomial degree of the deflection field in the finite-element model.
FE_DEGREE = 24
#: Largest (wavenumber × element length / degree) kept by the finite-element model.
#: Calibrated against the SS Rayleigh/Timoshenko closed forms (L/h = 5 to 300): with
#: degree 24 at 1.0 every kept eigenvalue is within 3e-10 (relative) of the exact value.
FE_RESOLUTION = 1.0
#: Cap on the finite-element unknowns (dense eigen-solution, O(n³) time, O(n²) memory).
FE_MAX_DOFS = 12000

@lru_cache(maxsize=8)
def _c0_basis(degree: int) -> np.ndarray:
    """Legendre coefficients (rows) of the hierarchical C0 basis of ``degree`` on [−1, 1]."""
    rows = np.zeros((degree + 1, degree + 1))
    rows[0, :2] = [0.5, -0.5]
    rows[1, :2] = [0.5, 0.5]
    for j in range(2, degree + 1):
        rows[j, j] = 1.0 / math.sqrt(2.0 * (2 * j - 1))
        rows[j, j - 2] = -rows[j, j]
    return rows


@lru_cache(maxsize=8)
def _c1_basis(degree: int) -> np.ndarray:
    """Legendre coefficients (rows) of the hierarchical C1 basis of ``degree`` on [−1, 1]."""
    hermite = [
        [0.5, -0.75, 0.0, 0.25],
        [0.25, -0.25, -0.25, 0.25],
        [0.5, 0.75, 0.0, -0.25],
        [-0.25, -0.25, 0.25, 0.25],
    ]
    rows = np.zeros((degree + 1, degree + 1))
    for i, power in enumerate(hermite):
        coefficients = legendre.poly2leg(power)
        rows[i, : coefficients.size] = coefficients
    for m in range(2, degree - 1):
        unit = np.zeros(m + 1)
        unit[m] = math.sqrt((2 * m + 1) / 2.0)
        coefficients = legendre.legint(unit, m=2, lbnd=-1.0)
        rows[2 + m, : coefficients.size] = coefficients
    return rows


def _evaluate(rows: np.ndarray, xi, derivative: int = 0) -> np.ndarray:
    """Basis values (n_basis, n_xi) from Legendre coefficient rows."""
    coefficients = rows.T
    if derivative:
        coefficients = legendre.legder(coefficients, m=derivative, axis=0)
    return legendre.legval(np.asarray(xi, dtype=float), coefficients).reshape(rows.shape[0], -1)


class _FiniteElementModes(ModeSet):
    """Modes stored as finite-element coefficient vectors on a uniform mesh."""

    def __init__(self, section, elements, degree, connectivity, vectors, frequencies,
                 resolved_frequency):
        self.section = section
        self.elements = int(elements)
        self.degree = int(degree)
        self.connectivity = connectivity
        self.vectors = vectors  # (n_dof_all, n_modes), constrained unknowns are zero
        self.frequencies = frequencies
        #: every mode up to this frequency [rad/s] is present and resolved
        self.resolved_frequency = float(resolved_frequency)

    def _locate(self, points):
        x = as_points(points)
        h = self.section.length / self.elements
        element = np.clip(np.floor(x / h).astype(int), 0, self.elements - 1)
        xi = 2.0 * (x - element * h) / h - 1.0
        return element, np.clip(xi, -1.0, 1.0), h

    def _field(self, points, count, which):
        n = self._count(count)
        element, xi, h = self._locate(points)
        out = np.empty((xi.size, n))
        timoshenko = self.section.theory == "timoshenko"
        p = self.degree
        if timoshenko:
            if which == "w":
                values = _evaluate(_c0_basis(p), xi)
                local = slice(0, p + 1)
            else:
                values = _evaluate(_c0_basis(p - 1), xi)
                local = slice(p + 1, 2 * p + 1)
            sign = 1.0
        else:
            rows = _c1_basis(p)
            if which == "w":
                values = _evaluate(rows, xi)
                sign = 1.0
            else:  # Ψ = −w' = −(2/h) dw/dξ
                values = _evaluate(rows, xi, 1) * (2.0 / h)
                sign = -1.0
            values = values * _c1_slope_scale(p, h)[:, None]
            local = slice(0, p + 1)
        for e in np.unique(element):
            here = element == e
            dofs = self.connectivity[e, local]
            out[here] = sign * values[:, here].T @ self.vectors[dofs, :n]
        return out

    def deflection(self, points, count=None):
        return self._field(points, count, "w")

    def rotation(self, points, count=None):
        return self._field(points, count, "psi")


def _c1_slope_scale(degree, h):
    """Physical slope unknowns: the ξ-slope Hermite functions are multiplied by h/2."""
    scale = np.ones(degree + 1)
    scale[1] = scale[3] = 0.5 * h
    return scale


def _bubbles_per_element(theory: str, degree: int) -> int:
    return 2 * degree - 3 if theory == "timoshenko" else degree - 3


def _layout(theory: str, elements: int, degree: int):
    """Banded numbering: (connectivity, nodal unknowns of every node, number of unknowns, half-bandwidth)."""
    bubbles = _bubbles_per_element(theory, degree)
    stride = 2 + bubbles
    e = np.arange(elements)
    base = e * stride
    node_dofs = np.arange(elements + 1)[:, None] * stride + np.arange(2)
    if theory == "timoshenko":
        bubbles_w = degree - 1
        connectivity = np.empty((elements, 2 * degree + 1), dtype=int)
        connectivity[:, 0], connectivity[:, 1] = base, base + stride
        connectivity[:, 2:degree + 1] = base[:, None] + 2 + np.arange(bubbles_w)
        connectivity[:, degree + 1], connectivity[:, degree + 2] = base + 1, base + stride + 1
        connectivity[:, degree + 3:] = base[:, None] + 2 + bubbles_w + np.arange(bubbles - bubbles_w)
    else:
        connectivity = np.empty((elements, degree + 1), dtype=int)
        connectivity[:, 0], connectivity[:, 1] = base, base + 1
        connectivity[:, 2], connectivity[:, 3] = base + stride, base + stride + 1
        connectivity[:, 4:] = base[:, None] + 2 + np.arange(bubbles)
    total = 2 * (elements + 1) + elements * bubbles
    return connectivity, node_dofs, total, bubbles + 3


def _element_matrices(section: BeamSection, h: float, degree: int):
    """Element stiffness and mass matrices [SI] in the local order of :func:`_layout`."""
    EI, rA, rI = section.bending_stiffness, section.mass_per_length, section.rotary_inertia
    jac = 0.5 * h
    xi, weights = legendre.leggauss(degree + 2)
    if section.theory == "timoshenko":
        S = section.shear_stiffness
        rows_w, rows_p = _c0_basis(degree), _c0_basis(degree - 1)
        Nw, dNw = _evaluate(rows_w, xi), _evaluate(rows_w, xi, 1) / jac
        Np, dNp = _evaluate(rows_p, xi), _evaluate(rows_p, xi, 1) / jac
        zw, zp = np.zeros_like(Nw), np.zeros_like(Np)
        shear = np.concatenate([dNw, Np])  # ψ + w'
        bending = np.concatenate([zw, dNp])  # ψ'
        deflection = np.concatenate([Nw, zp])
        rotation = np.concatenate([zw, Np])
        Ke = (EI * (bending * weights) @ bending.T + S * (shear * weights) @ shear.T) * jac
        Me = (rA * (deflection * weights) @ deflection.T
              + rI * (rotation * weights) @ rotation.T) * jac
    else:
        rows = _c1_basis(degree)
        scale = _c1_slope_scale(degree, h)[:, None]
        N = _evaluate(rows, xi) * scale
        dN = _evaluate(rows, xi, 1) * scale / jac
        ddN = _evaluate(rows, xi, 2) * scale / jac**2
        Ke = EI * (ddN * weights) @ ddN.T * jac
        Me = (rA * (N * weights) @ N.T + rI * (dN * weights) @ dN.T) * jac
    return Ke, Me


def _assemble(section: BeamSection, elements: int, degree: int):
    """Sparse global K, M [SI] (banded numbering), connectivity, free unknowns, nodes."""
    connectivity, node_dofs, total, bandwidth = _layout(section.theory, elements, degree)
    Ke, Me = _element_matrices(section, section.length / elements, degree)
    local = connectivity.shape[1]
    rows = np.repeat(connectivity, local, axis=1).ravel()
    cols = np.tile(connectivity, (1, local)).ravel()
    K = scipy.sparse.coo_matrix((np.tile(Ke.ravel(), elements), (rows, cols)),
                                shape=(total, total)).tocsc()
    M = scipy.sparse.coo_matrix((np.tile(Me.ravel(), elements), (rows, cols)),
                                shape=(total, total)).tocsc()
    fixed = []
    for end, node in ((section.supports[0], 0), (section.supports[1], elements)):
        if end in "cs":
            fixed.append(node_dofs[node, 0])  # w = 0
        if end == "c":
            fixed.append(node_dofs[node, 1])  # ψ = 0 (Timoshenko) or w' = 0 (C1)
    free = np.setdiff1d(np.arange(total), fixed)
    return K, M, connectivity, free, node_dofs, bandwidth


def _rigid_vectors(section: BeamSection, elements: int, total: int, node_dofs) -> np.ndarray:
    """FE coefficient vectors of translation (w = 1) and rotation (w = x − L/2, ψ = −1)."""
    L = section.length
    x = np.linspace(0.0, L, elements + 1)
    vectors = np.zeros((total, 2))
    vectors[node_dofs[:, 0], 0] = 1.0
    vectors[node_dofs[:, 0], 1] = x - 0.5 * L
    # ψ = −1 (Timoshenko) or w' = +1 (C1 slope unknowns)
    vectors[node_dofs[:, 1], 1] = -1.0 if section.theory == "timoshenko" else 1.0
    return vectors


@lru_cache(maxsize=4)  # near FE_MAX_DOFS one solution holds ~150 MB of vectors
def _fe_solution(section: BeamSection, elements: int, degree: int) -> _FiniteElementModes:
    """Eigen-solution of the FE model: all modes up to its resolved frequency (cached per section and mesh)."""
    K, M, connectivity, free, node_dofs, width = _assemble(section, elements, degree)
    Kf, Mf = K[free][:, free], M[free][:, free]
    L, EI, rA = section.length, section.bending_stiffness, section.mass_per_length
    resolved = frequency_at_wavenumber(section, FE_RESOLUTION * degree * elements / L)
    upper = resolved**2 * (1.0 + 1e-9)
    reference = EI * (math.pi / L) ** 4 / rA
    free_free = section.supports == "ff"
    eigenvalues, vectors_free = eigenpairs_below(Kf, Mf, upper, width, reference, free_free)
    vectors = np.zeros((K.shape[0], eigenvalues.size))
    vectors[free] = vectors_free
    if free_free:
        # the two rigid-body modes are exact in the FE space: replace the computed
        # (degenerate, round-off-rotated) pair by translation and rotation, M-normalised
        if eigenvalues.size < 3 or not abs(eigenvalues[1]) < 1e-6 * eigenvalues[2]:
            raise RuntimeError("free-free FE model does not show exactly two rigid-body modes")
        rigid = _rigid_vectors(section, elements, K.shape[0], node_dofs)
        rigid = rigid / np.sqrt(np.einsum("ij,ij->j", rigid, M @ rigid))
        elastic = vectors[:, 2:]
        elastic -= rigid @ (rigid.T @ (M @ elastic))  # round-off rigid content
        vectors[:, :2] = rigid
        eigenvalues[:2] = 0.0
    eigenvalues = np.maximum(eigenvalues, 0.0)
    return _FiniteElementModes(section, elements, degree, connectivity, vectors,
                               np.sqrt(eigenvalues), resolved)


def finite_element_mode_count(section: BeamSection, max_frequency: float, *, degree: int = FE_DEGREE) -> int:
    """Number of modes :func:`finite_element_modes` returns at or below ``max_frequency`` [rad/s],
    counted by Sylvester's inertia without solving for them."""
    require_nonnegative("max_frequency", max_frequency, "rad/s")
    elements, _ = _capped_elements(section, _elements_needed(section, max_frequency, 1, degree), degree)
    K, M, _, free, _, width = _assemble(section, elements, degree)
    resolved = frequency_at_wavenumber(section, FE_RESOLUTION * degree * elements / section.length)
    upper = min(float(max_frequency) ** 2, resolved**2 * (1.0 + 1e-9))
    return count_below(K[free][:, free], M[free][:, free], width, upper)


def finite_element_resolution_limit(section: BeamSection, *, degree: int = FE_DEGREE) -> float:
    """Highest frequency [rad/s] the largest finite-element model (:data:`FE_MAX_DOFS` unknowns) resolves."""
    per_element = 2 + _bubbles_per_element(section.theory, degree)
    elements = max(2, (FE_MAX_DOFS - 2) // per_element)
    while elements > 2 and _dofs(section, elements, degree) > FE_MAX_DOFS:
        elements -= 1
    return frequency_at_wavenumber(section, FE_RESOLUTION * degree * elements / section.length)


def _capped_elements(section: BeamSection, elements: int, degree: int) -> tuple[int, bool]:
    """``elements``, or fewer so the model has at most :data:`FE_MAX_DOFS` unknowns; and whether it was capped."""
    capped = _dofs(section, elements, degree) > FE_MAX_DOFS
    if capped:
        while elements > 2 and _dofs(section, elements, degree) > FE_MAX_DOFS:
            elements -= 1
    return elements, capped


def _elements_needed(section: BeamSection, max_frequency: float, min_modes: int,
                     degree: int) -> int:
    L = section.length
    k_needed = max(float(largest_wavenumber(section, max_frequency)),
                   (int(min_modes) + 2) * math.pi / L)
    needed = max(2, math.ceil(k_needed * L / (FE_RESOLUTION * degree)))
    # round up on a ~×1.25 grid so that nearby requests share one cached solution
    grid = 2
    while grid < needed:
        grid = max(grid + 1, int(math.ceil(grid * 1.25)))
    return grid


def _dofs(section: BeamSection, elements: int, degree: int) -> int:
    return 2 * (elements + 1) + elements * _bubbles_per_element(section.theory, degree)

def finite_element_modes(section: BeamSection, max_frequency: float, min_modes: int = 1,
                         *, degree: int = FE_DEGREE) -> ModeSet:
    """Rayleigh/Timoshenko (or, for verification, Euler) modes by p-version finite elements.

    All modes with ω ≤ ``max_frequency`` [rad/s] (at least ``min_modes``) that the mesh
    resolves; at most :data:`FE_MAX_DOFS` unknowns (beyond that a warning, and the rest is
    carried by the residual compliance). Relative frequency error ≤ 3e-10 against the
    closed forms for 5 ≤ L/h ≤ 300 (docs/physics.rst).
    """
    elements = _elements_needed(section, max_frequency, min_modes, degree)
    while True:
        elements, capped = _capped_elements(section, elements, degree)
        solution = _fe_solution(section, elements, degree)
        if len(solution) >= min_modes or capped:
            break
        elements = _elements_needed(section, 0.0, 2 * max(int(min_modes), len(solution)), degree)
    if capped and (solution.resolved_frequency < max_frequency or len(solution) < min_modes):
        warnings.warn(
            f"beam finite-element model capped at FE_MAX_DOFS = {FE_MAX_DOFS} unknowns: "
            f"modes above {solution.resolved_frequency:.6g} rad/s are not resolved and are "
            f"left to the residual compliance (requested max_frequency = "
            f"{float(max_frequency):.6g} rad/s, min_modes = {int(min_modes)})",
            stacklevel=3,
        )
    cutoff = cutoff_with_min_modes(solution.frequencies, max_frequency, min_modes)
    keep = int(np.searchsorted(solution.frequencies, cutoff, side="right"))
    return _FiniteElementModes(section, solution.elements, solution.degree, solution.connectivity,
                               solution.vectors[:, :keep], solution.frequencies[:keep],
                               solution.resolved_frequency)

