"""Finite-difference Rayleigh beam with a layered elastic-plastic section (seed 000).

Equation (spec section 5, with the sign of the moment term made consistent — see below)
--------------------------------------------------------------------------------------
::

    ρA ẅ − ρI ẅ'' + C ẇ − M'' = p(x, t),    M = b ∫ σ z dz,    ε = −z w''

``w`` and ``z`` point in the impact direction; ``M`` is the sagging moment
(:mod:`impactmaps.fd.section`), so in the elastic range ``M = −EI w''`` and the equation is
the Rayleigh beam ``ρA ẅ − ρI ẅ'' + C ẇ + EI w'''' = p``. (PHYSICS.md §5 writes ``+M''``
together with ``M = b∫σz dz`` and ``ε = −z w''``; those three statements give
``ρA ẅ − EI w'''' = p``, which is ill-posed. ``+M''`` is right only for the hogging
moment ``M = EI w''``. The static test ``PL³/(48EI)`` pins the sign used here.)
Shear deformation is not modelled (Rayleigh theory: no shear deflection).

Space: nodes ``x_j = j Δx``, ``Δx = L/N_l``, curvature ``κ_j = (w_{j−1} − 2w_j + w_{j+1})/Δx²``,
moment from the section at each node, ``M''`` by the same second difference. Written as a
Lagrangian system: the nodal equations are ``M_mass ẅ + C_d ẇ + f_int(w) = f_ext`` with

* ``f_int = ∂U/∂w``, ``U = Σ_j c_j Δx u(κ_j)`` (``u`` the section energy per length,
  ``∂u/∂κ = −M``), i.e. ``f_int,m = −(M_{m−1} − 2M_m + M_{m+1})/Δx`` at interior nodes;
* ``M_mass = ρA Δx diag(m_j) + (ρI/Δx) T``: translational mass (``m_j = 1``, ½ at an end
  node) plus rotary inertia from the slopes of the ``N_l`` intervals
  (``½ ρI Σ Δx ((ẇ_{j+1} − ẇ_j)/Δx)²``), ``T`` the tridiagonal ``(−1, 2, −1)`` matrix with
  one fewer interval at each end — a tridiagonal SPD matrix;
* ``C_d = C Δx diag(m_j)``; the contact force is a **nodal point load** on the node nearest
  the impact point (``p = F/Δx`` over that node's tributary length, as in the modal
  solver's point load).

Boundary conditions, exactly as implemented (per end):

* ``"ss"`` — ``w_0 = 0`` (node removed from the unknowns) and ``M_0 = 0`` (no section at
  the support node: ``c_0 = 0``). Equivalent to the antisymmetric ghost ``w_{−1} = −w_1``.
* ``"cc"`` — ``w_0 = 0`` and ``w'_0 = 0`` through the symmetric ghost ``w_{−1} = w_1``:
  ``κ_0 = 2 w_1/Δx²``, the support section counts with half its tributary length
  (``c_0 = ½``). Its moment enters node 1 as ``−M_0/Δx``, the standard ghost-node stencil.
* ``"free"`` — ``M_0 = 0`` (``c_0 = 0``) and ``Q_0 = 0`` through the ghosts
  ``M_{−1} = M_1`` and ``ẅ_{−1} = ẅ_1`` (the central difference of the Rayleigh shear
  force ``Q = M' + ρI ẅ'``, from ``ρA ẅ − (M' + ρI ẅ')' = p``, vanishes at the end
  node); the full-node equation with these ghosts
  is exactly the half-mass equation ``(ρAΔx/2) ẅ_0 + (ρI/Δx)(ẅ_0 − ẅ_1) = M_1/Δx``
  produced by the Lagrangian form.

Time: central differences in velocity form,
``(M_mass + ½Δt C_d) v^{n+½} = (M_mass − ½Δt C_d) v^{n−½} + Δt (f_ext^n − f_int(w^n))``,
``w^{n+1} = w^n + Δt v^{n+½}``: one tridiagonal solve per step with a matrix factorised
once (LDLᵀ). The sphere is a rigid body advanced by the same scheme,
``m (v_s^{n+½} − v_s^{n−½}) = Δt (−F^n + m g)``; ``F^n = law(α^n = u^n − w_k^n; α_max)``
with ``α_max`` the largest earlier indentation, updated after each step.

Energy ledger: with half-step kinetic energies the scheme satisfies a discrete energy
identity exactly, the strain-energy/plastic-work split of the section is exact
(trapezoidal plastic work), and the contact energy is taken from the law at its
``α_max``; the ledger therefore closes up to the O(Δt²) difference between the discrete
contact work ``Σ F^n (α^{n+1} − α^{n−1})/2`` and the law's ``∫F dα`` — 1e-6 … 4e-5 of
the impact energy in the tests (roundoff without contact). It is a genuine check: a support stencil inconsistent with the
energy, or a wrong internal-force sign, breaks it.

Gravity (``gravity=True``) acts on the sphere only, ``g = 9.80665 m/s²`` (standard gravity,
CGPM 1901). The beam's self-weight is *not* included: deflections are measured from the
beam's static equilibrium under its own weight (exact by superposition for the elastic
beam; for the plastic beam the self-weight stresses — peak ρAgL²/8 ≈ 0.5 % of M_y for
the seed-000 steel beam — are neglected).
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, field

import numba
import numpy as np
import pandas as pd
import scipy.linalg

from .._checks import (
    require_choice,
    require_finite,
    require_in_range,
    require_nonnegative,
    require_positive,
)
from ..contact.base import KERNEL_TYPE, ContactLaw
from ..contact.linear import _linear_kernel
from ..solvers.modal import reference_contact_stiffness
from ..solvers.result import ImpactResult
from .section import LayeredSection, return_map

__all__ = [
    "FDBeam",
    "FDDetails",
    "FDResponse",
    "simulate_fd",
    "simulate_fd_response",
    "stable_time_step",
    "grid_frequency_bound",
    "STANDARD_GRAVITY",
]

#: Standard acceleration of gravity [m/s²] (3rd CGPM, 1901).
STANDARD_GRAVITY = 9.80665

_SUPPORTS = ("ss", "cc", "free")
#: Default time step never exceeds this fraction of 1/ω_c (ω_c: contact–node frequency at
#: the expected peak stiffness), i.e. ≥ 60 steps per contact oscillation period.
_CONTACT_RESOLUTION = 0.1
_MAX_INTERVALS = 10_000


# =====================================================================================
# Beam definition
# =====================================================================================
@dataclass(frozen=True)
class FDBeam:
    """A uniform rectangular beam for the finite-difference solver (SI units).

    Parameters
    ----------
    length : float
        Span L [m].
    width : float
        Section width b [m].
    height : float
        Section height h [m], in the impact direction.
    youngs_modulus : float
        E [Pa].
    density : float
        ρ [kg/m³].
    yield_strength : float
        Uniaxial yield stress σ_y [Pa] (> 0 even when ``plastic=False``).
    hardening_modulus : float, optional
        Linear kinematic plastic modulus H [Pa] (0: elastic–perfectly plastic).
    damping_per_length : float, optional
        Viscous damping coefficient per unit length C [N s/m²] (≥ 0).
    supports : str or (str, str), optional
        ``"ss"`` (simply supported, default), ``"cc"`` (clamped) or ``"free"``, for both
        ends or as a (left, right) pair.
    n_elements : int, optional
        Number of grid intervals N_l along the span (≥ 4, default 200).
    n_half_layers : int, optional
        N_h, half the number of section layers (≥ 2, default 10).
    plastic : bool, optional
        Layered elastic-plastic section if True (default). If False the section is
        linear elastic with the exact ``EI = E b h³/12`` (no layers; the plastic work is
        identically zero) — the model to compare with modal solutions.
    poisson_ratio : float, optional
        ν [-], not used by the beam; kept so that the beam can serve as the target
        material of a contact law, e.g. ``law_for_sphere("stronge", sphere, beam)``
        (default 0.3).
    """

    length: float
    width: float
    height: float
    youngs_modulus: float
    density: float
    yield_strength: float
    hardening_modulus: float = 0.0
    damping_per_length: float = 0.0
    supports: str | tuple = "ss"
    n_elements: int = 200
    n_half_layers: int = 10
    plastic: bool = True
    poisson_ratio: float = 0.3

    def __post_init__(self):
        require_positive("length", self.length, "m")
        require_positive("width", self.width, "m")
        require_positive("height", self.height, "m")
        require_positive("youngs_modulus", self.youngs_modulus, "Pa")
        require_positive("density", self.density, "kg/m^3")
        require_positive("yield_strength", self.yield_strength, "Pa")
        require_nonnegative("hardening_modulus", self.hardening_modulus, "Pa")
        require_nonnegative("damping_per_length", self.damping_per_length, "N s/m^2")
        require_in_range("poisson_ratio", self.poisson_ratio, -1.0, 0.5,
                         low_inclusive=False, high_inclusive=False)
        supports = self.supports
        if isinstance(supports, str):
            supports = (supports, supports)
        supports = tuple(supports)
        if len(supports) != 2:
            raise ValueError(
                f"supports = {self.supports!r} is invalid: give one of {_SUPPORTS} or a (left, right) pair"
            )
        for end in supports:
            require_choice("supports", end, _SUPPORTS)
        object.__setattr__(self, "supports", supports)
        for name, low in (("n_elements", 4), ("n_half_layers", 2)):
            value = getattr(self, name)
            require_finite(name, value)
            if int(value) != value:
                raise ValueError(f"{name} = {value!r} is invalid: must be an integer >= {low}")
            require_in_range(name, value, low, np.inf)
            object.__setattr__(self, name, int(value))
        object.__setattr__(self, "plastic", bool(self.plastic))

    @classmethod
    def from_material(cls, length, width, height, material, **options) -> "FDBeam":
        """Build from a material object.

        Parameters
        ----------
        length, width, height : float
            L, b, h [m].
        material : material-like
            Duck-typed: ``youngs_modulus`` [Pa], ``density`` [kg/m³], ``yield_strength``
            [Pa] and ``poisson_ratio`` [-].
        **options
            Any other :class:`FDBeam` field.
        """
        values = {}
        for attribute in ("youngs_modulus", "density", "yield_strength", "poisson_ratio"):
            try:
                values[attribute] = getattr(material, attribute)
            except AttributeError:
                raise ValueError(
                    f"material = {material!r} has no attribute {attribute!r}: FDBeam needs "
                    "youngs_modulus [Pa], density [kg/m^3], yield_strength [Pa], poisson_ratio [-]"
                ) from None
        if values["yield_strength"] is None:
            raise ValueError(
                "material.yield_strength = None is invalid: valid range is (0, inf) [Pa] "
                "(use plastic=False with any positive value for an elastic beam)"
            )
        values.update(options)
        return cls(length, width, height, **values)

    # -- derived properties ------------------------------------------------------------
    @property
    def section(self) -> LayeredSection:
        """The layered cross-section."""
        return LayeredSection(self.width, self.height, self.youngs_modulus, self.yield_strength,
                              self.hardening_modulus, self.n_half_layers)

    @property
    def area(self) -> float:
        """A = b h [m²]."""
        return self.width * self.height

    @property
    def second_moment(self) -> float:
        """I = b h³/12 [m⁴]."""
        return self.width * self.height**3 / 12.0

    @property
    def bending_stiffness(self) -> float:
        """Elastic EI of the model [N m²]: exact if ``plastic=False``, else the layered
        (midpoint-rule) ``E I (1 − 1/(4N_h²))``."""
        if self.plastic:
            return self.youngs_modulus * self.section.layered_second_moment
        return self.youngs_modulus * self.second_moment

    @property
    def mass_per_length(self) -> float:
        """ρA [kg/m]."""
        return self.density * self.area

    @property
    def rotary_inertia_per_length(self) -> float:
        """ρI [kg m]."""
        return self.density * self.second_moment

    @property
    def mass(self) -> float:
        """Beam mass ρAL [kg]."""
        return self.mass_per_length * self.length

    @property
    def grid_spacing(self) -> float:
        """Δx = L/N_l [m]."""
        return self.length / self.n_elements

    @property
    def node_positions(self) -> np.ndarray:
        """x_j = j Δx, j = 0…N_l [m]."""
        return np.linspace(0.0, self.length, self.n_elements + 1)

    @property
    def bar_wave_speed(self) -> float:
        """c_0 = sqrt(E/ρ) [m/s], the short-wave limit of the Rayleigh beam."""
        return math.sqrt(self.youngs_modulus / self.density)

    def rayleigh_frequency(self, wavenumber):
        """Rayleigh-beam dispersion ω(k) = sqrt(EI k⁴/(ρA + ρI k²)) [rad/s] (exact EI).

        For simply supported ends ``k = nπ/L`` gives the natural frequencies.
        """
        k = np.asarray(wavenumber, dtype=float)
        ei = self.youngs_modulus * self.second_moment
        return np.sqrt(ei * k**4 / (self.mass_per_length + self.rotary_inertia_per_length * k**2))

    def rayleigh_group_velocity(self, wavenumber):
        """Group velocity dω/dk [m/s] of Rayleigh-beam flexural waves at wavenumber k [1/m]."""
        k = np.asarray(wavenumber, dtype=float)
        ei = self.youngs_modulus * self.second_moment
        ra, ri = self.mass_per_length, self.rotary_inertia_per_length
        omega = self.rayleigh_frequency(k)
        return ei * k**3 * (4 * ra + 2 * ri * k**2) / (2 * omega * (ra + ri * k**2) ** 2)

    def simply_supported_frequency(self, mode):
        """Natural frequency ω_n [rad/s] of the SS Rayleigh beam, ``k = nπ/L``."""
        return self.rayleigh_frequency(np.asarray(mode, dtype=float) * np.pi / self.length)

    def static_point_compliance(self, position=None) -> float:
        """Static deflection per unit point load at ``position`` [m/N], SS ends only.

        ``a² b²/(3 E I L)`` with ``a = x0``, ``b = L − x0`` (Rayleigh = Euler statics;
        exact EI). Default position: mid-span (``L³/(48EI)``).
        """
        if self.supports != ("ss", "ss"):
            raise ValueError(f"supports = {self.supports!r}: static_point_compliance needs ('ss', 'ss')")
        x0 = 0.5 * self.length if position is None else float(position)
        require_in_range("position", x0, 0.0, self.length, unit="m")
        return x0**2 * (self.length - x0) ** 2 / (
            3.0 * self.youngs_modulus * self.second_moment * self.length
        )

    def stability_limit(self) -> float:
        """Stable central-difference step of the beam alone, ``2/sqrt(λ*)`` [s].

        λ* is the rigorous upper bound of the highest grid frequency squared
        (:func:`grid_frequency_bound`; ≤ 1.2 % above the exact value for N_l ≥ 50), so
        the step is safe for every support combination; for a Rayleigh beam it tends to
        ``Δx/c_0`` (bar-wave CFL) when ``Δx ≪ h``.
        """
        return 2.0 / math.sqrt(_grid(self).max_eigenvalue)


# =====================================================================================
# Grid operators (built once per beam)
# =====================================================================================
@dataclass(frozen=True)
class _Grid:
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


def grid_frequency_bound(beam: "FDBeam") -> float:
    """Rigorous upper bound of the highest grid frequency squared, λ* [rad²/s²].

    ``λ* = 16 EI / (Δx⁴ (ρA + 4ρI/Δx²))`` — the symbol of the interior operator at the
    grid Nyquist wavenumber. Proof that ``wᵀKw ≤ λ* wᵀMw`` for every support
    combination: with ``S = Σ c_j (Δx² κ_j)²``, ``T = Σ_intervals (Δw)²``,
    ``P = Σ m_j w_j²``, the inequality ``(a − b)² ≤ 2a² + 2b²`` and the fact that each
    interval enters at most two curvatures with total weight ≤ 4 (also at a clamped end,
    where ``c_0 = ½`` and ``Δx²κ_0 = 2Δw``) give ``S ≤ 4T``; each node enters at most two
    intervals, and an end node (mass weight ½) only one, so ``T ≤ 4P``. Hence
    ``wᵀKw = (EI/Δx³) S ≤ (EI/Δx³) 4T`` and
    ``wᵀMw = ρAΔx P + (ρI/Δx) T ≥ (ρAΔx/4 + ρI/Δx) T``, whose ratio is λ*. For simple
    supports the bound exceeds the true top eigenvalue by a factor
    ``1/sin⁴((N_l − 1)π/(2N_l))`` to leading order (1.2 % at N_l = 50, 0.05 % at 200).
    The model's elastic EI is used (the largest tangent: layers unload elastically).
    """
    dx = beam.grid_spacing
    return 16.0 * beam.bending_stiffness / (
        dx**4 * (beam.mass_per_length + 4.0 * beam.rotary_inertia_per_length / dx**2))


@functools.lru_cache(maxsize=64)
def _grid(beam: FDBeam) -> _Grid:
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
    return _Grid(n, dx, constrained, mass_weight, section_weight, stencil, mass_diag, mass_off,
                 damping_diag, grid_frequency_bound(beam), band)


def _factorise(grid: _Grid, time_step: float):
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


def _inverse_mass_at(grid: _Grid, node: int) -> float:
    """(M_mass⁻¹)_kk on the free nodes [1/kg]: the node's effective inverse mass.

    The factorised matrix keeps the constrained nodes as decoupled identity rows, so one
    O(N) tridiagonal solve with the unit vector gives the free-node inverse exactly.
    """
    pivots, lower = _factorise(grid, 0.0)
    unit = np.zeros(grid.n_nodes)
    unit[node] = 1.0
    return float(_tridiagonal_solve(pivots, lower, unit)[node])


# =====================================================================================
# The compiled time loop
# =====================================================================================
@numba.njit(cache=True)
def _section_moments(plastic, curvature, old_curvature, section_weight, stress, back,
                     plastic_strain, plastic_work_node, virgin, z, layer_area, youngs_modulus,
                     yield_strength, hardening_modulus, bending_stiffness, moment):
    """Update every node's section to the new curvature; return Σ c_j ΔW_p,j [J/m].

    Fast path: a node that has never yielded (``virgin``) has the elastic layer stresses
    ``σ_i = −E z_i κ`` exactly, so while its outermost layer stays below yield its moment
    is ``−E I_h κ`` and the layers are not touched; they are filled in (at the old
    curvature) the step the node first yields, and by :func:`_materialise` at the end.
    """
    total_work = 0.0
    n = curvature.shape[0]
    n_layers = z.shape[0]
    outer = abs(z[0])
    for j in range(n):
        if section_weight[j] == 0.0:
            moment[j] = 0.0
            continue
        if not plastic:
            moment[j] = -bending_stiffness * curvature[j]
            continue
        if virgin[j]:
            if youngs_modulus * outer * abs(curvature[j]) <= yield_strength:
                moment[j] = -bending_stiffness * curvature[j]
                continue
            virgin[j] = False
            for i in range(n_layers):
                stress[j, i] = -youngs_modulus * z[i] * old_curvature[j]
        dk = curvature[j] - old_curvature[j]
        m = 0.0
        work = 0.0
        for i in range(n_layers):
            s, b, p, wk = return_map(stress[j, i], back[j, i], -z[i] * dk, youngs_modulus,
                                     yield_strength, hardening_modulus)
            stress[j, i] = s
            back[j, i] = b
            plastic_strain[j, i] += p
            m += s * z[i]
            work += wk
        moment[j] = m * layer_area
        plastic_work_node[j] += work * layer_area
        total_work += section_weight[j] * work * layer_area
    return total_work


@numba.njit(cache=True)
def _materialise(plastic, curvature, virgin, stress, z, youngs_modulus):
    """Write the layer stresses of never-yielded nodes, σ_i = −E z_i κ."""
    if not plastic:
        return
    for j in range(curvature.shape[0]):
        if virgin[j]:
            for i in range(z.shape[0]):
                stress[j, i] = -youngs_modulus * z[i] * curvature[j]


@numba.njit(cache=True)
def _curvatures(w, stencil, inv_dx2, out):
    n = w.shape[0]
    for j in range(n):
        value = stencil[1, j] * w[j]
        if j > 0:
            value += stencil[0, j] * w[j - 1]
        if j < n - 1:
            value += stencil[2, j] * w[j + 1]
        out[j] = value * inv_dx2


@numba.njit(cache=True)
def _elastic_energy(plastic, curvature, section_weight, stress, layer_area, youngs_modulus,
                    bending_stiffness, dx):
    total = 0.0
    for j in range(curvature.shape[0]):
        if section_weight[j] == 0.0:
            continue
        if plastic:
            s2 = 0.0
            for i in range(stress.shape[1]):
                s2 += stress[j, i] * stress[j, i]
            total += section_weight[j] * dx * layer_area * s2 / (2.0 * youngs_modulus)
        else:
            total += section_weight[j] * dx * 0.5 * bending_stiffness * curvature[j] ** 2
    return total


_F8 = numba.types.float64
_VEC = numba.types.Array(_F8, 1, "C")
_MAT = numba.types.Array(_F8, 2, "C")
_I8 = numba.types.int64
_BOOL = numba.types.boolean
# The loop takes the kernel as the first-class function type KERNEL_TYPE (a function
# pointer, impactmaps.contact.base), not as a dispatcher, so one compiled loop serves every
# law and numba's on-disk cache works across processes.
_INTEGRATE_SIGNATURE = numba.types.Tuple((_VEC, _VEC))(
    KERNEL_TYPE, _VEC, _BOOL, _F8, _F8, _F8, _I8,  # kernel … impact_node
    _VEC, _F8, _I8, _F8,  # external_force, dt, n_steps, dx
    numba.types.Array(_BOOL, 1, "C"), _VEC, _MAT,  # constrained, section_weight, stencil
    _VEC, _VEC, _VEC, _VEC, _VEC,  # mass_diag, mass_off, damping_diag, pivots, lower
    _BOOL, _VEC, _F8, _F8, _F8, _F8, _F8,  # plastic, z, layer_area, E, σ_y, H, EI
    _MAT, _MAT, _MAT, _VEC, numba.types.Array(_BOOL, 1, "C"),  # stress … work, virgin
    _VEC, _VEC,  # w, v
    _I8, numba.types.Array(_I8, 1, "C"), _VEC,  # stride, gauge_left, gauge_weight
    _VEC, _VEC, _VEC, _VEC, _VEC, _VEC, _VEC, _MAT, _MAT,  # records
    _MAT,  # intervals
)


@numba.njit(_INTEGRATE_SIGNATURE, cache=True)
def _integrate(kernel, params, has_impactor, impactor_mass, velocity, gravity, impact_node,
               external_force, dt, n_steps, dx, constrained, section_weight, stencil,
               mass_diag, mass_off, damping_diag, pivots, lower, plastic, z, layer_area,
               youngs_modulus, yield_strength, hardening_modulus, bending_stiffness,
               stress, back, plastic_strain, plastic_work_node, virgin, w, v, stride,
               gauge_left, gauge_weight, rec_time, rec_force, rec_alpha, rec_u, rec_vs,
               rec_wk, rec_vk, rec_gauge_w, rec_gauge_k, intervals):
    n = w.shape[0]
    inv_dx2 = 1.0 / (dx * dx)
    curvature = np.zeros(n)
    new_curvature = np.zeros(n)
    moment = np.zeros(n)
    force_vector = np.zeros(n)
    rhs = np.zeros(n)
    v_new = np.zeros(n)
    n_gauges = gauge_left.shape[0]

    u = 0.0
    vs = velocity - 0.5 * dt * gravity  # v_s^{-1/2}
    alpha_max = 0.0
    peak_force = 0.0
    peak_time = 0.0
    in_contact = False
    n_intervals = 0
    separation_velocity = np.nan
    damping_work = 0.0
    contact_work_beam = 0.0
    contact_work_sphere = 0.0
    gravity_work = 0.0
    plastic_work = 0.0
    record = 0
    last_alpha = 0.0
    last_force = 0.0
    peak_step = -2
    force_before_peak = 0.0
    force_after_peak = 0.0

    for step in range(n_steps):
        t = step * dt
        # -- section: curvature and moments at w^n --------------------------------
        _curvatures(w, stencil, inv_dx2, new_curvature)
        plastic_work += dx * _section_moments(
            plastic, new_curvature, curvature, section_weight, stress, back, plastic_strain,
            plastic_work_node, virgin, z, layer_area, youngs_modulus, yield_strength,
            hardening_modulus, bending_stiffness, moment)
        for j in range(n):
            curvature[j] = new_curvature[j]
        # -- contact force at α^n -------------------------------------------------
        force = 0.0
        alpha = 0.0
        if has_impactor:
            alpha = u - w[impact_node]
            force, _stiffness = kernel(alpha, alpha_max, params)
            if alpha > alpha_max:
                alpha_max = alpha
        load = force
        if external_force.shape[0] > 0:
            load += external_force[step]
        if force > peak_force:
            peak_force = force
            peak_time = t
            peak_step = step
            force_before_peak = last_force
        elif step == peak_step + 1:
            force_after_peak = force
        last_force = force
        # -- internal forces f = −Bᵀ(c Δx M) ---------------------------------------
        for j in range(n):
            force_vector[j] = 0.0
        for j in range(n):
            q = section_weight[j] * moment[j] / dx
            if q == 0.0:
                continue
            if j > 0:
                force_vector[j - 1] -= q * stencil[0, j]
            force_vector[j] -= q * stencil[1, j]
            if j < n - 1:
                force_vector[j + 1] -= q * stencil[2, j]
        # -- RHS and tridiagonal solve ----------------------------------------------
        for j in range(n):
            if constrained[j]:
                rhs[j] = 0.0
                continue
            value = (mass_diag[j] - 0.5 * dt * damping_diag[j]) * v[j]
            if j > 0:
                value += mass_off[j - 1] * v[j - 1]
            if j < n - 1:
                value += mass_off[j] * v[j + 1]
            value -= dt * force_vector[j]
            if j == impact_node:
                value += dt * load
            rhs[j] = value
        for j in range(1, n):
            rhs[j] -= lower[j] * rhs[j - 1]
        v_new[n - 1] = rhs[n - 1] / pivots[n - 1]
        for j in range(n - 2, -1, -1):
            v_new[j] = rhs[j] / pivots[j] - lower[j + 1] * v_new[j + 1]
        # -- work accumulators (exact discrete identities) ---------------------------
        for j in range(n):
            vm = 0.5 * (v[j] + v_new[j])
            damping_work += dt * damping_diag[j] * vm * vm
        vk_mid = 0.5 * (v[impact_node] + v_new[impact_node])
        contact_work_beam += dt * load * vk_mid
        # -- sphere ------------------------------------------------------------------
        vs_mid = vs
        if has_impactor:
            vs_new = vs + dt * (gravity - force / impactor_mass)
            vs_mid = 0.5 * (vs + vs_new)
            gravity_work += impactor_mass * gravity * dt * vs_mid
            contact_work_sphere += dt * force * vs_mid
            u += dt * vs_new
            vs = vs_new
        # -- contact intervals --------------------------------------------------------
        if force > 0.0 and not in_contact:
            in_contact = True
            if n_intervals < intervals.shape[0]:
                intervals[n_intervals, 0] = t
                intervals[n_intervals, 1] = np.nan
            n_intervals += 1
        elif force <= 0.0 and in_contact:
            in_contact = False
            if n_intervals <= intervals.shape[0]:
                intervals[n_intervals - 1, 1] = t
            separation_velocity = vs_mid
        # -- record at step n -------------------------------------------------------------
        if step % stride == 0 and record < rec_time.shape[0]:
            rec_time[record] = t
            rec_force[record] = load if not has_impactor else force
            rec_alpha[record] = alpha
            rec_u[record] = u - dt * vs if has_impactor else 0.0
            rec_vs[record] = vs_mid
            rec_wk[record] = w[impact_node]
            rec_vk[record] = vk_mid
            for g in range(n_gauges):
                i = gauge_left[g]
                th = gauge_weight[g]
                rec_gauge_w[record, g] = (1.0 - th) * w[i] + th * w[i + 1]
                rec_gauge_k[record, g] = (1.0 - th) * curvature[i] + th * curvature[i + 1]
            record += 1
        # -- advance --------------------------------------------------------------------
        for j in range(n):
            v[j] = v_new[j]
            w[j] += dt * v_new[j]
        last_alpha = alpha

    # -- closing the ledger at t_N: internal work of the last half step -------------
    _materialise(plastic, curvature, virgin, stress, z, youngs_modulus)
    elastic_before = _elastic_energy(plastic, curvature, section_weight, stress, layer_area,
                                     youngs_modulus, bending_stiffness, dx)
    _curvatures(w, stencil, inv_dx2, new_curvature)
    half_work = 0.0
    for j in range(n):
        half_work += 0.5 * section_weight[j] * dx * (-moment[j]) * (new_curvature[j] - curvature[j])
    last_plastic = dx * _section_moments(
        plastic, new_curvature, curvature, section_weight, stress, back, plastic_strain,
        plastic_work_node, virgin, z, layer_area, youngs_modulus, yield_strength,
        hardening_modulus, bending_stiffness, moment)
    for j in range(n):
        curvature[j] = new_curvature[j]
    _materialise(plastic, curvature, virgin, stress, z, youngs_modulus)
    final_alpha = u - w[impact_node] if has_impactor else 0.0
    # parabolic refinement of the sampled peak (sampling error O(Δt³) instead of O(Δt²))
    curvature_of_peak = force_before_peak - 2.0 * peak_force + force_after_peak
    if peak_step >= 1 and peak_step + 1 < n_steps and curvature_of_peak < 0.0 \
            and force_before_peak > 0.0 and force_after_peak > 0.0:
        offset = 0.5 * (force_before_peak - force_after_peak) / curvature_of_peak
        peak_force -= 0.25 * (force_before_peak - force_after_peak) * offset
        peak_time += offset * dt

    scalars = np.array([
        alpha_max, peak_force, peak_time, float(n_intervals), separation_velocity,
        1.0 if in_contact else 0.0, u, vs, damping_work, contact_work_beam,
        contact_work_sphere, gravity_work, plastic_work, last_plastic, elastic_before,
        half_work, float(record), final_alpha, last_alpha,
    ])
    return scalars, curvature


# =====================================================================================
# Results
# =====================================================================================
@dataclass(frozen=True)
class FDDetails:
    """What only the finite-difference beam knows of an impact (``ImpactResult.details``).

    Attributes
    ----------
    permanent_beam_deflection : float
        Permanent deflection at the impact node [m]: the static deflection of the
        unloaded beam computed from the final state by an elastic unloading step
        (``w_res = w − K_e⁻¹ f_int(w)``, the residual curvature's deflection), *not* a
        time average, so residual vibration does not affect it.
    final_mean_deflection : float
        Diagnostic: mean deflection at the impact node over the last 20 % of the record [m].
    energy : dict
        The ledger [J]: ``impact_kinetic_energy`` (½ m V0²), ``gravity_work``,
        ``impactor_kinetic_energy`` (end of record), ``rebound_kinetic_energy`` (at the
        final separation, not part of the balance), ``beam_kinetic_energy``,
        ``beam_elastic_energy``, ``beam_plastic_work``, ``contact_dissipation`` (the law's
        ``dissipated_energy(α_max)``, evaluated from its kernel — loading work minus the
        work recovered on the unloading curve), ``contact_stored_energy`` (non-zero only
        if still in contact), ``damping_work``, ``contact_work_discrete`` (diagnostic
        ``Σ F Δα``), and ``energy_balance_error``: (sum of the final terms − input)/impact
        energy [-].
    residual : pandas.DataFrame
        Per node: ``x_m, final_deflection_m, permanent_deflection_m,
        residual_curvature_1_m, max_plastic_strain, plastic_work_J_m``.
    impact_position, impact_node_position : float
        Requested impact point and the node that carries the load [m].
    stability_limit : float
        The estimated stability limit of the explicit scheme [s].
    gauge_positions : tuple of float
        Gauge positions [m] (history columns ``gauge{g}_deflection_m``,
        ``gauge{g}_strain``: axial strain of the far face ``z = +h/2``, ``−(h/2) w''``,
        tension positive).
    """

    permanent_beam_deflection: float
    final_mean_deflection: float
    energy: dict
    residual: pd.DataFrame
    impact_position: float
    impact_node_position: float
    stability_limit: float
    gauge_positions: tuple

    @property
    def plastic_zone(self):
        """(x_min, x_max) [m] of the nodes that have yielded, or ``None``."""
        plastic = self.residual["max_plastic_strain"].to_numpy() > 0
        if not plastic.any():
            return None
        x = self.residual["x_m"].to_numpy()[plastic]
        return float(x.min()), float(x.max())

    def summary(self) -> dict:
        """The finite-difference scalars with unit-suffixed keys (the whole ledger)."""
        out = {"permanent_beam_deflection_m": float(self.permanent_beam_deflection)}
        out.update({f"{k}_J" if k != "energy_balance_error" else k: float(v)
                    for k, v in self.energy.items()})
        return out


@dataclass(frozen=True)
class FDResponse:
    """Response of an :class:`FDBeam` to a prescribed point load (no impactor).

    Attributes
    ----------
    history : pandas.DataFrame
        ``time_s, load_N, deflection_at_load_m, velocity_at_load_m_s`` and the gauge
        columns as in :class:`FDDetails`.
    final_deflection : ndarray
        Deflection of every node at the end of the run [m].
    energy : dict
        ``load_work, beam_kinetic_energy, beam_elastic_energy, beam_plastic_work,
        damping_work, energy_balance_error`` (the last relative to ``load_work`` plus the
        initial energy) [J].
    time_step : float
        Δt [s].
    load_node_position : float
        Node carrying the load [m].
    """

    history: pd.DataFrame
    final_deflection: np.ndarray
    energy: dict
    time_step: float
    load_node_position: float


# =====================================================================================
# Front ends
# =====================================================================================
@numba.njit(numba.types.UniTuple(_VEC, 2)(KERNEL_TYPE, _VEC, _VEC, _VEC), cache=True)
def _kernel_curve(kernel, params, alpha, alpha_max):
    """Force and tangent stiffness of a kernel along (α, α_max) pairs (function-pointer
    version of :func:`impactmaps.contact.evaluate_kernel`, compiled once for all laws)."""
    force = np.empty(alpha.shape[0])
    stiffness = np.empty(alpha.shape[0])
    for i in range(alpha.shape[0]):
        force[i], stiffness[i] = kernel(alpha[i], alpha_max[i], params)
    return force, stiffness


def _contact_stiffness_bound(law: ContactLaw, params, impactor_mass: float, velocity: float) -> float:
    """Largest tangent contact stiffness [N/m] expected in the impact.

    The indentation is bounded by the rigid-target value at *twice* the impact energy
    (margin for a beam that swings back into the sphere); the bound is the largest
    tangent on the loading curve up to it and on the unloading curve leaving it (for
    plastic laws the unloading curve is much stiffer than the loading curve). The
    loading work is integrated from the kernel (trapezoidal rule on 4096 points).
    """
    target = 2.0 * 0.5 * impactor_mass * velocity**2
    fraction = np.linspace(0.0, 1.0, 4097)[1:]
    alpha = 1e-12
    for _ in range(200):
        grid = alpha * fraction
        force, _k = _kernel_curve(law.kernel, params, grid, grid)
        if np.trapezoid(np.concatenate(([0.0], force)), np.concatenate(([0.0], grid))) >= target:
            break
        alpha *= 2.0
    else:
        raise ValueError(
            f"law = {law!r} does not store the impact energy {target:g} J at any indentation up to {alpha:g} m"
        )
    _f, loading = _kernel_curve(law.kernel, params, grid, grid)
    _f, unloading = _kernel_curve(law.kernel, params, grid * (1.0 - 1e-12), np.full(grid.size, alpha))
    bound = float(max(np.max(loading), np.max(unloading)))
    if not np.isfinite(bound):
        raise ValueError(f"law = {law!r} returns a non-finite tangent stiffness up to α = {alpha:g} m")
    return bound


def _kernel_work(kernel, params, low, high, alpha_max=None, points=20001):
    """∫ F dα [J] from ``low`` to ``high`` on the loading curve (``alpha_max=None``) or on
    the unloading curve leaving ``alpha_max`` (trapezoidal rule, ``points`` nodes)."""
    if high <= low:
        return 0.0
    alpha = np.linspace(low, high, points)
    alpha[0] = max(low, 1e-12 * high)  # the kernels return 0 at α = 0 exactly (no tension)
    history = alpha if alpha_max is None else np.full(points, float(alpha_max))
    force, _k = _kernel_curve(kernel, params, alpha, history)
    return float(np.trapezoid(force, alpha))


def _contact_energies(kernel, params, alpha_max, alpha_now=None):
    """Contact-zone energies from the law's kernel at its history ``alpha_max`` [m].

    Returns ``permanent_indentation`` α_f (bisection for the start of the unloading
    curve), ``dissipation`` = loading work to α_max − work recovered unloading from α_max
    to α_f (the law's ``dissipated_energy(α_max)``; evaluated from the same kernel that
    the time loop uses, 20001-point trapezoid, relative error < 1e-8), and ``stored`` =
    work recoverable from the current indentation ``alpha_now`` (0 when separated).
    """
    if alpha_max <= 0.0:
        return dict(permanent_indentation=0.0, dissipation=0.0, stored=0.0)
    below = np.array([0.0])
    history = np.array([float(alpha_max)])
    low, high = 0.0, float(alpha_max)
    if _kernel_curve(kernel, params, np.array([1e-9 * alpha_max]), history)[0][0] > 0.0:
        floor = 0.0
    else:
        for _ in range(80):
            mid = 0.5 * (low + high)
            below[0] = mid
            if _kernel_curve(kernel, params, below, history)[0][0] > 0.0:
                high = mid
            else:
                low = mid
        floor = high
    loading = _kernel_work(kernel, params, 0.0, alpha_max)
    recovered = _kernel_work(kernel, params, floor, alpha_max, alpha_max)
    stored = 0.0
    if alpha_now is not None and alpha_now > floor:
        stored = _kernel_work(kernel, params, floor, min(alpha_now, alpha_max), alpha_max)
    return dict(permanent_indentation=floor, dissipation=loading - recovered, stored=stored)


def _gauges(beam: FDBeam, gauge_positions):
    positions = tuple(float(x) for x in np.atleast_1d(np.asarray(gauge_positions, float)))
    for x in positions:
        require_in_range("gauge_positions", x, 0.0, beam.length, unit="m")
    scaled = np.asarray(positions, float) / beam.grid_spacing
    left = np.minimum(np.floor(scaled).astype(np.int64), beam.n_elements - 1)
    weight = scaled - left
    return positions, np.ascontiguousarray(left), np.ascontiguousarray(weight)


def _node_for(beam: FDBeam, grid: _Grid, position, name):
    x0 = 0.5 * beam.length if position is None else position
    dx = grid.dx
    low = 0.5 * dx if grid.constrained[0] else 0.0
    high = beam.length - 0.5 * dx if grid.constrained[-1] else beam.length
    require_in_range(name, x0, low, high, low_inclusive=not grid.constrained[0],
                     high_inclusive=not grid.constrained[-1], unit="m")
    node = int(np.clip(round(float(x0) / dx), 0, beam.n_elements))
    return float(x0), node


def _choose_time_step(beam, grid, time_step, safety_factor, contact_rate):
    """(time step, stability limit): ω_max² = λ_beam + k_c (M⁻¹_kk + 1/m)."""
    require_in_range("safety_factor", safety_factor, 0.0, 1.0, low_inclusive=False)
    limit = 2.0 / math.sqrt(grid.max_eigenvalue + contact_rate)
    if time_step is None:
        step = safety_factor * limit
        if contact_rate > 0:
            step = min(step, _CONTACT_RESOLUTION / math.sqrt(contact_rate))
        return step, limit
    require_in_range("time_step", time_step, 0.0, limit, low_inclusive=False, unit="s")
    return float(time_step), limit


def _layer_data(beam):
    section = beam.section
    return (np.ascontiguousarray(section.layer_positions),
            section.width * section.layer_thickness, section.n_layers)


def _run_loop(beam, grid, dt, n_steps, kernel, params, has_impactor, impactor_mass, velocity,
              gravity, node, external, w0, v0, stride, gauge_left, gauge_weight):
    z, layer_area, n_layers = _layer_data(beam)
    n = grid.n_nodes
    shape = (n, n_layers) if beam.plastic else (n, 1)
    stress = np.zeros(shape)
    back = np.zeros(shape)
    plastic_strain = np.zeros(shape)
    plastic_work_node = np.zeros(n)
    virgin = np.ones(n, dtype=bool)
    pivots, lower = _factorise(grid, dt)
    n_records = (n_steps - 1) // stride + 1
    rec = [np.zeros(n_records) for _ in range(7)]
    rec_gw = np.zeros((n_records, gauge_left.size))
    rec_gk = np.zeros((n_records, gauge_left.size))
    intervals = np.full((_MAX_INTERVALS, 2), np.nan)
    w = w0.copy()
    v = v0.copy()
    scalars, curvature = _integrate(
        kernel, params, has_impactor, impactor_mass, velocity, gravity, node, external, dt,
        n_steps, grid.dx, grid.constrained, grid.section_weight, grid.stencil, grid.mass_diag,
        grid.mass_off, grid.damping_diag, pivots, lower, beam.plastic, z, layer_area,
        beam.youngs_modulus, beam.yield_strength, beam.hardening_modulus,
        beam.bending_stiffness, stress, back, plastic_strain, plastic_work_node, virgin, w, v,
        stride,
        gauge_left, gauge_weight, *rec, rec_gw, rec_gk, intervals,
    )
    scalars = dict(zip(_SCALAR_NAMES, scalars))
    n_intervals = int(scalars["n_intervals"])
    if n_intervals > _MAX_INTERVALS:
        warnings.warn(f"{n_intervals} contacts; only the first {_MAX_INTERVALS} intervals are kept",
                      stacklevel=3)
    return dict(scalars=scalars, curvature=curvature, w=w, v=v, stress=stress, back=back,
                plastic_strain=plastic_strain, plastic_work_node=plastic_work_node,
                records=rec, gauge_w=rec_gw, gauge_k=rec_gk,
                intervals=intervals[: min(n_intervals, _MAX_INTERVALS)])


#: Names of the scalar vector returned by :func:`_integrate`, in order.
_SCALAR_NAMES = (
    "alpha_max", "peak_force", "peak_time", "n_intervals", "separation_velocity",
    "in_contact", "impactor_displacement", "impactor_velocity_half", "damping_work",
    "contact_work_beam", "contact_work_sphere", "gravity_work", "plastic_work",
    "last_plastic_increment", "elastic_energy_before_last", "half_step_work", "records",
    "final_alpha", "last_alpha",
)


def _kinetic(grid, v):
    mv = grid.mass_diag * v
    mv[:-1] += grid.mass_off * v[1:]
    mv[1:] += grid.mass_off * v[:-1]
    return 0.5 * float(v @ mv)


def _beam_energies(grid, out):
    s = out["scalars"]
    # W_p through step N−1 plus half of the last increment (the ledger is taken at t_{N−½})
    before_last = s["plastic_work"] - s["last_plastic_increment"]
    plastic = before_last + 0.5 * s["last_plastic_increment"]
    # exact discrete internal work Σ f_int^n·(w^{n+1} − w^{n−1})/2
    internal = s["elastic_energy_before_last"] + before_last + s["half_step_work"]
    return dict(beam_kinetic_energy=_kinetic(grid, out["v"]),
                beam_elastic_energy=internal - plastic,
                beam_plastic_work=plastic)


def _gauge_columns(out, beam, n):
    cols = {}
    for g in range(out["gauge_w"].shape[1]):
        cols[f"gauge{g}_deflection_m"] = out["gauge_w"][:n, g]
        cols[f"gauge{g}_strain"] = -0.5 * beam.height * out["gauge_k"][:n, g]
    return cols


def _residual_state(beam, grid, out):
    """Unload the final state elastically: w_res = w − K_e⁻¹ f_int(w) on the free nodes."""
    n = grid.n_nodes
    w = out["w"]
    curvature = out["curvature"]
    section = beam.section
    if beam.plastic:
        moment = section.moment(out["stress"]) * (grid.section_weight > 0)
    else:
        moment = -beam.bending_stiffness * curvature * (grid.section_weight > 0)
    q = grid.section_weight * moment / grid.dx
    f_int = np.zeros(n)
    f_int[:-1] -= q[1:] * grid.stencil[0, 1:]
    f_int -= q * grid.stencil[1]
    f_int[1:] -= q[:-1] * grid.stencil[2, :-1]
    free = grid.free
    correction = np.zeros(n)
    rigid_modes = not ((grid.constrained[0] and grid.constrained[-1]) or "cc" in beam.supports)
    if rigid_modes:  # e.g. free–free or ss–free: minimum-norm correction (dense, rare)
        k_free = grid.stiffness_dense()[np.ix_(free, free)]
        correction[free] = np.linalg.lstsq(k_free, f_int[free], rcond=None)[0]
    else:  # K_e is pentadiagonal SPD: banded Cholesky with the supports as identity rows
        band = grid.stiffness_banded.copy()
        for m in np.flatnonzero(grid.constrained):
            band[2, m] = 1.0
            band[1, m] = 0.0
            band[0, m] = 0.0
            if m + 1 < n:
                band[1, m + 1] = 0.0
            if m + 2 < n:
                band[0, m + 2] = 0.0
        rhs = np.where(grid.constrained, 0.0, f_int)
        correction = scipy.linalg.solveh_banded(band, rhs)
    residual_w = w - correction
    stencil = grid.stencil
    residual_k = stencil[1] * residual_w
    residual_k[1:] += stencil[0, 1:] * residual_w[:-1]
    residual_k[:-1] += stencil[2, :-1] * residual_w[1:]
    residual_k /= grid.dx**2
    if beam.plastic:  # check that the unloading stays elastic
        dk = residual_k - curvature
        unloaded = out["stress"] - beam.youngs_modulus * np.outer(dk, section.layer_positions)
        relative = np.abs(unloaded - out["back"]) - beam.yield_strength
        if np.max(relative[grid.section_weight > 0], initial=-1.0) > 1e-6 * beam.yield_strength:
            warnings.warn(
                "elastic unloading to the permanent deflection re-yields some layers; "
                "permanent_beam_deflection is approximate", stacklevel=3)
    max_plastic = np.max(np.abs(out["plastic_strain"]), axis=1)
    return pd.DataFrame({
        "x_m": np.linspace(0.0, beam.length, n),
        "final_deflection_m": w,
        "permanent_deflection_m": residual_w,
        "residual_curvature_1_m": residual_k,
        "max_plastic_strain": max_plastic,
        "plastic_work_J_m": out["plastic_work_node"],
    })


def simulate_fd(beam: FDBeam, law: ContactLaw, impactor_mass, velocity, impact_position=None, *,
                duration, time_step=None, safety_factor=0.8, gauge_positions=(),
                gravity=False, history_stride=1) -> ImpactResult:
    """Impact of a rigid sphere on a finite-difference Rayleigh beam.

    Parameters
    ----------
    beam : FDBeam
        The beam (grid, section, supports, damping).
    law : ContactLaw
        Contact law of a single case (``kernel_parameters`` one-dimensional). The
        seed-000 model is the refined Stronge law with the beam's yield stress,
        ``impactmaps.contact.law_for_sphere("stronge", sphere, beam)``; a linear or Hertz
        law with ``plastic=False`` is the model that the modal Rayleigh-beam solver
        reproduces. Only ``law.kernel``, ``law.kernel_parameters`` and ``law.name`` are
        used (the contact energies are integrated from the kernel).
    impactor_mass : float
        Sphere mass m [kg] (> 0).
    velocity : float
        Impact velocity V0 [m/s] (> 0), in the +w direction; the sphere touches the
        beam (α = 0) at t = 0.
    impact_position : float, optional
        x0 [m] (default mid-span); the load goes to the nearest node, which must not be a
        supported node (valid range (Δx/2, L − Δx/2) with supported ends).
    duration : float
        Simulated time [s] (> 0); the run always covers it (sub-impacts may occur late).
    time_step : float, optional
        Forced Δt [s]; must not exceed the stability limit (``ValueError`` naming both).
        Default: ``safety_factor × limit``, capped at 0.1/ω_c (ω_c the contact–node
        frequency at the expected peak stiffness) for accuracy.
    safety_factor : float, optional
        Fraction (0, 1] of the stability limit used by the default step (0.8).
    gauge_positions : sequence of float, optional
        Positions [m] where deflection and far-face strain are recorded.
    gravity : bool, optional
        Standard gravity on the sphere (drop tests); the beam's self-weight is not
        included (module notes).
    history_stride : int, optional
        Record every ``history_stride``-th step (≥ 1). Scalars always use every step.

    Returns
    -------
    ImpactResult
        ``method = "finite-difference"``; ``details`` is an :class:`FDDetails`.

    Notes
    -----
    Stability limit: ``Δt ≤ 2/sqrt(λ* + k_c (M⁻¹_kk + 1/m))`` with λ* the closed-form
    upper bound of the highest eigenvalue of the elastic grid operator (with rotary
    inertia; :func:`grid_frequency_bound`) and k_c the largest contact tangent stiffness
    expected (rigid-target indentation at twice the impact energy, loading and unloading
    curves). For the linearised system the bound is rigorous (Rayleigh quotients add);
    the contact part rests on the k_c estimate.
    """
    if not isinstance(beam, FDBeam):
        raise ValueError(f"beam = {beam!r} is not an FDBeam")
    if not isinstance(law, ContactLaw):
        raise ValueError(f"law = {law!r} is not a ContactLaw")
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    require_positive("duration", duration, "s")
    stride = _stride(history_stride)
    params = np.ascontiguousarray(np.asarray(law.kernel_parameters, dtype=float))
    if params.ndim != 1:
        raise ValueError(
            f"law.kernel_parameters has shape {params.shape}: simulate_fd needs a single case "
            "(1-D parameters), not a batch"
        )
    impactor_mass = float(impactor_mass)
    velocity = float(velocity)
    grid = _grid(beam)
    x0, node = _node_for(beam, grid, impact_position, "impact_position")
    positions, gauge_left, gauge_weight = _gauges(beam, gauge_positions)
    contact_stiffness = _contact_stiffness_bound(law, params, impactor_mass, velocity)
    contact_rate = contact_stiffness * (_inverse_mass_at(grid, node) + 1.0 / impactor_mass)
    dt, limit = _choose_time_step(beam, grid, time_step, safety_factor, contact_rate)
    n_steps = int(math.ceil(float(duration) / dt))
    g = STANDARD_GRAVITY if gravity else 0.0

    n = grid.n_nodes
    out = _run_loop(beam, grid, dt, n_steps, law.kernel, params, True, impactor_mass, velocity,
                    g, node, np.zeros(0), np.zeros(n), np.zeros(n), stride, gauge_left, gauge_weight)
    s = out["scalars"]
    alpha_max, peak_force, peak_time = s["alpha_max"], s["peak_force"], s["peak_time"]
    still_in_contact = bool(s["in_contact"])
    n_rec = int(s["records"])
    time, force, alpha, u, vs, wk, vk = (r[:n_rec] for r in out["records"])
    history = pd.DataFrame({
        "time_s": time,
        "force_N": force,
        "indentation_m": alpha,
        "impactor_velocity_m_s": vs,
        "impactor_displacement_m": u,
        "target_displacement_m": wk,
        "target_velocity_m_s": vk,
        **_gauge_columns(out, beam, n_rec),
    })

    intervals = out["intervals"]
    separation_velocity = s["separation_velocity"]
    if still_in_contact or intervals.shape[0] == 0:
        if intervals.shape[0] == 0:
            warnings.warn("the sphere never touched the beam", stacklevel=2)
        else:
            warnings.warn(
                f"the record ends in contact at t = {n_steps * dt:g} s: rebound velocity, "
                "restitution and energy loss are undefined (nan); increase duration",
                stacklevel=2)
        separation_velocity = np.nan
    rebound_velocity = -separation_velocity

    # -- energy ledger -----------------------------------------------------------------
    impact_energy = 0.5 * impactor_mass * velocity**2
    final_alpha = s["final_alpha"]
    contact = _contact_energies(law.kernel, params, alpha_max, final_alpha if still_in_contact else None)
    dissipation, stored = contact["dissipation"], contact["stored"]
    energy = dict(
        impact_kinetic_energy=impact_energy,
        gravity_work=float(s["gravity_work"]),
        impactor_kinetic_energy=0.5 * impactor_mass * s["impactor_velocity_half"] ** 2,
        rebound_kinetic_energy=(0.5 * impactor_mass * separation_velocity**2
                                if np.isfinite(separation_velocity) else np.nan),
        **_beam_energies(grid, out),
        contact_dissipation=dissipation,
        contact_stored_energy=stored,
        damping_work=float(s["damping_work"]),
        contact_work_discrete=float(s["contact_work_sphere"] - s["contact_work_beam"]),
    )
    total = (energy["impactor_kinetic_energy"] + energy["beam_kinetic_energy"]
             + energy["beam_elastic_energy"] + energy["beam_plastic_work"]
             + dissipation + stored + energy["damping_work"])
    energy["energy_balance_error"] = (total - impact_energy - energy["gravity_work"]) / impact_energy

    residual = _residual_state(beam, grid, out)
    tail = time >= 0.8 * time[-1]
    contact_intervals = np.asarray(intervals, float).reshape(-1, 2)
    return ImpactResult(
        history=history,
        peak_force=float(peak_force),
        peak_time=float(peak_time),
        contact_intervals=contact_intervals,
        max_indentation=float(alpha_max),
        permanent_indentation=contact["permanent_indentation"],
        rebound_velocity=float(rebound_velocity),
        energy_transferred=energy["beam_kinetic_energy"] + energy["beam_elastic_energy"],
        contact_dissipation=dissipation,
        damping_work=energy["damping_work"],
        energy_balance_error=energy["energy_balance_error"],
        impactor_mass=impactor_mass,
        velocity=velocity,
        contact_frequency=float(np.sqrt(reference_contact_stiffness(law, impactor_mass, velocity)
                                        / impactor_mass)),
        end_time=float(n_steps * dt),
        time_limit_reached=still_in_contact,
        time_step=dt,
        method="finite-difference",
        settings=dict(beam=beam, law=law.name, duration=float(duration), gravity=g,
                      history_stride=stride, safety_factor=float(safety_factor),
                      n_steps=n_steps, contact_stiffness_bound=contact_stiffness),
        details=FDDetails(
            permanent_beam_deflection=float(residual["permanent_deflection_m"].iloc[node]),
            final_mean_deflection=float(np.mean(wk[tail])),
            energy=energy,
            residual=residual,
            impact_position=x0,
            impact_node_position=node * grid.dx,
            stability_limit=limit,
            gauge_positions=positions,
        ),
    )


def stable_time_step(beam: FDBeam, law: ContactLaw, impactor_mass, velocity,
                     impact_position=None, safety_factor=0.8):
    """The default time step of :func:`simulate_fd` and the stability limit [s].

    Parameters
    ----------
    beam, law, impactor_mass, velocity, impact_position, safety_factor
        As for :func:`simulate_fd`.

    Returns
    -------
    time_step, stability_limit : float
        ``min(safety × limit, 0.1/ω_c)`` and ``2/sqrt(λ* + k_c (M⁻¹_kk + 1/m))`` [s].
    """
    require_positive("impactor_mass", impactor_mass, "kg")
    require_positive("velocity", velocity, "m/s")
    params = np.ascontiguousarray(np.asarray(law.kernel_parameters, dtype=float))
    if params.ndim != 1:
        raise ValueError(f"law.kernel_parameters has shape {params.shape}: need a single case")
    grid = _grid(beam)
    _x0, node = _node_for(beam, grid, impact_position, "impact_position")
    stiffness = _contact_stiffness_bound(law, params, float(impactor_mass), float(velocity))
    rate = stiffness * (_inverse_mass_at(grid, node) + 1.0 / float(impactor_mass))
    return _choose_time_step(beam, grid, None, safety_factor, rate)


def _stride(history_stride):
    require_finite("history_stride", history_stride)
    if int(history_stride) != history_stride:
        raise ValueError(f"history_stride = {history_stride!r} is invalid: must be an integer >= 1")
    require_in_range("history_stride", history_stride, 1, np.inf)
    return int(history_stride)


def simulate_fd_response(beam: FDBeam, load=None, load_position=None, *, duration,
                         time_step=None, safety_factor=0.8, initial_deflection=None,
                         gauge_positions=(), history_stride=1) -> FDResponse:
    """Response of the beam to a prescribed nodal point load and/or initial deflection.

    Parameters
    ----------
    beam : FDBeam
        The beam.
    load : callable, optional
        ``load(t) -> force [N]`` vectorised over an array of times [s], applied (in the
        +w direction) at the node nearest ``load_position``. Default: no load.
    load_position : float, optional
        x [m] of the load (default mid-span); same valid range as ``impact_position``.
    duration : float
        Simulated time [s].
    time_step : float, optional
        Forced Δt [s] (≤ the stability limit of the beam).
    safety_factor : float, optional
        Fraction of the stability limit for the default step (0.8).
    initial_deflection : callable or array_like, optional
        ``w(x)`` [m] at t = 0 (callable of node positions, or values at the N_l + 1
        nodes); the beam starts at rest. Supported nodes are set to 0.
    gauge_positions : sequence of float, optional
        Gauge positions [m].
    history_stride : int, optional
        Record every ``history_stride``-th step.

    Returns
    -------
    FDResponse
    """
    if not isinstance(beam, FDBeam):
        raise ValueError(f"beam = {beam!r} is not an FDBeam")
    require_positive("duration", duration, "s")
    stride = _stride(history_stride)
    grid = _grid(beam)
    x_load, node = _node_for(beam, grid, load_position, "load_position")
    positions, gauge_left, gauge_weight = _gauges(beam, gauge_positions)
    dt, _limit = _choose_time_step(beam, grid, time_step, safety_factor, 0.0)
    n_steps = int(math.ceil(float(duration) / dt))
    times = np.arange(n_steps) * dt
    external = np.zeros(n_steps)
    if load is not None:
        external = np.array(np.broadcast_to(np.asarray(load(times), float), (n_steps,)))
        require_finite("load(t)", external, "N")
    n = grid.n_nodes
    w0 = np.zeros(n)
    if initial_deflection is not None:
        values = initial_deflection(beam.node_positions) if callable(initial_deflection) \
            else initial_deflection
        w0 = np.array(np.broadcast_to(np.asarray(values, float), (n,)))
        require_finite("initial_deflection", w0, "m")
        w0[grid.constrained] = 0.0
    # v^{-1/2} = −½Δt a⁰ with M a⁰ = f_ext⁰ − K w⁰ (elastic start; the beam is at rest)
    pivots, lower = _factorise(grid, 0.0)
    elastic_force = grid.stiffness_times(w0)
    accel_rhs = -elastic_force.copy()
    accel_rhs[node] += external[0] if n_steps else 0.0
    accel_rhs[grid.constrained] = 0.0
    accel = _tridiagonal_solve(pivots, lower, accel_rhs)
    v0 = -0.5 * dt * accel
    # initial strain energy, corrected by the start-up half step of the discrete identity
    initial_energy = 0.5 * float(w0 @ elastic_force) - 0.5 * dt * float(elastic_force @ v0)
    out = _run_loop(beam, grid, dt, n_steps, _linear_kernel, np.ones(1), False, 1.0, 0.0, 0.0,
                    node, external, w0, v0, stride, gauge_left, gauge_weight)
    s = out["scalars"]
    n_rec = int(s["records"])
    time, force, _a, _u, _vs, wk, vk = (r[:n_rec] for r in out["records"])
    history = pd.DataFrame({
        "time_s": time, "load_N": force, "deflection_at_load_m": wk,
        "velocity_at_load_m_s": vk, **_gauge_columns(out, beam, n_rec),
    })
    energies = _beam_energies(grid, out)
    # the kinetic energy of the start-up half step ½ v^{-1/2} M v^{-1/2} is part of the input
    start_kinetic = _kinetic(grid, v0)
    load_work = float(s["contact_work_beam"])  # work of the applied load
    total = energies["beam_kinetic_energy"] + energies["beam_elastic_energy"] \
        + energies["beam_plastic_work"] + float(s["damping_work"])
    reference = load_work + initial_energy + start_kinetic
    scale = max(abs(load_work) + initial_energy, 1e-300)
    energy = dict(load_work=load_work, initial_energy=initial_energy + start_kinetic, **energies,
                  damping_work=float(s["damping_work"]), energy_balance_error=(total - reference) / scale)
    return FDResponse(history=history, final_deflection=out["w"].copy(), energy=energy,
                      time_step=dt, load_node_position=node * grid.dx)


def _tridiagonal_solve(pivots, lower, rhs):
    y = rhs.astype(float).copy()
    for j in range(1, y.size):
        y[j] -= lower[j] * y[j - 1]
    x = np.empty_like(y)
    x[-1] = y[-1] / pivots[-1]
    for j in range(y.size - 2, -1, -1):
        x[j] = y[j] / pivots[j] - lower[j + 1] * x[j + 1]
    return x
