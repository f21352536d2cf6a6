"""Rectangular, specially orthotropic plates (Kirchhoff or Mindlin) as impact targets.

Simply supported plates (``edges="SSSS"``) use the Navier solution (PHYSICS.md 3.3):
closed-form Kirchhoff frequencies, or per half-wave pair (m, n) the 3×3 Mindlin
eigenproblem of seed 001 eqs (13)–(15). Any other combination of simply supported (S),
clamped (C) and free (F) edges uses the Rayleigh–Ritz basis of
:mod:`impactmaps.targets.ritz` (Kirchhoff only).

Conventions: the plate occupies ``0 ≤ x ≤ a``, ``0 ≤ y ≤ b``; the edge code lists the
edges x = 0, y = 0, x = a, y = b in that order; ``s_m(x) = sin(mπx/a)``,
``c_m(x) = cos(mπx/a)``; A55 is the xz and A44 the yz transverse shear stiffness.

Static point stiffness (for λ, PHYSICS.md 1 and 3.3): always the *classical*
(shear-rigid) value, also for ``theory="mindlin"``: with transverse shear the deflection
under a point load diverges logarithmically, so the Mindlin point stiffness is zero.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import scipy.special

from .._checks import (
    require_choice,
    require_in_range,
    require_nonnegative,
    require_positive,
)
from ..dimensionless import (
    effective_plate_stiffness,
    impactor_mass_for_plate,
    loss_factor_plate,
)
from ..solvers import asymptotes
from . import ritz
from .base import InfiniteImpact, ModalBasis, Target
from .options import PLATE_THEORIES

__all__ = ["Plate", "classical_static_compliance", "navier_static_compliance", "PLATE_THEORIES",
           "STATIC_RITZ_FUNCTIONS"]

#: Ritz functions per direction for the static point compliance of non-SSSS plates.
#: Must be ≥ :data:`impactmaps.targets.ritz.MAX_FUNCTIONS` so that the static basis
#: contains every modal basis (then the residual compliance is never negative).
STATIC_RITZ_FUNCTIONS = 40

#: Terms of the outer (single) series of :func:`navier_static_compliance`.
_NAVIER_STATIC_TERMS = 20000


# ---------------------------------------------------------------------------------
# Navier (SSSS) helpers
# ---------------------------------------------------------------------------------
def _sin_pi(t):
    """sin(π t) with exact zeros at integer t and argument reduction (mod 2) first."""
    t = np.asarray(t, dtype=float)
    reduced = np.remainder(t, 2.0)
    result = np.sin(np.pi * reduced)
    return np.where(reduced == np.round(reduced), 0.0, result)


def _sum_sin_squared_over(c, theta):
    """Σ_{n≥1} sin²(nθ)/(n² + c²) for complex c (Re c > 0) and 0 ≤ θ ≤ π.

    From Σ cos(nx)/(n² + c²) = π cosh(c(π − x))/(2c sinh(cπ)) − 1/(2c²), 0 ≤ x ≤ 2π:
    ``(π/(4c)) (1 − u)(1 − v)/(1 − uv)``, ``u = e^{−2cθ}``, ``v = e^{−2c(π−θ)}``
    (overflow-free and without cancellation).
    """
    one_minus_u = -np.expm1(-2.0 * c * theta)
    one_minus_v = -np.expm1(-2.0 * c * (np.pi - theta))
    one_minus_uv = -np.expm1(-2.0 * c * np.pi)
    return np.pi / (4.0 * c) * one_minus_u * one_minus_v / one_minus_uv


def _derivative_sum_sin_squared_over(c, theta):
    """d/d(c²) of :func:`_sum_sin_squared_over` = −Σ sin²(nθ)/(n² + c²)²."""
    u = np.exp(-2.0 * c * theta)
    v = np.exp(-2.0 * c * (np.pi - theta))
    one_minus_u = -np.expm1(-2.0 * c * theta)
    one_minus_v = -np.expm1(-2.0 * c * (np.pi - theta))
    one_minus_uv = -np.expm1(-2.0 * c * np.pi)
    ratio = one_minus_u * one_minus_v / one_minus_uv
    d_ratio = (
        (2.0 * theta * u * one_minus_v + 2.0 * (np.pi - theta) * v * one_minus_u) / one_minus_uv
        - ratio * 2.0 * np.pi * u * v / one_minus_uv
    )
    d_sum_dc = -np.pi / (4.0 * c**2) * ratio + np.pi / (4.0 * c) * d_ratio
    return d_sum_dc / (2.0 * c)


def _inner_series(p, length_y, y0, D11, D22, H):
    """Σ_{n≥1} s_n(y0)² / (D11 p⁴ + 2H p² q_n² + D22 q_n⁴), q_n = nπ/b, in closed form.

    The denominator factorises as ``D22 (q² + ρ1)(q² + ρ2)`` with
    ``ρ1,2 = p² (H ± sqrt(H² − D11 D22))/D22`` (complex conjugates when H² < D11 D22);
    partial fractions reduce the sum to :func:`_sum_sin_squared_over`. Near the isotropic
    double root (``|H² − D11 D22| < 1e-10 D11 D22``) the divided difference is replaced
    by the derivative at the mean root; the two branches balance truncation against
    cancellation and are accurate to ≲ 5e-11 relative at the switch.
    """
    p = np.asarray(p, dtype=float)
    theta = math.pi * y0 / length_y
    scale = (length_y / math.pi) ** 2  # q_n² + ρ = (π/b)² (n² + ρ b²/π²)
    root = np.sqrt(complex(H * H - D11 * D22))
    separation = abs(root) / math.sqrt(D11 * D22)
    p2 = p**2
    if separation < 1e-5:
        rho_mean = p2 * H / D22
        c = np.sqrt(rho_mean * scale + 0j)
        # Σ s²/((q²+ρ)²) = −dG/dρ with G(ρ) = scale Σ s²/(n² + ρ scale)
        value = -scale**2 * _derivative_sum_sin_squared_over(c, theta)
        return np.real(value) / D22
    rho1 = p2 * (H + root) / D22
    rho2 = p2 * (H - root) / D22
    c1 = np.sqrt(rho1 * scale)
    c2 = np.sqrt(rho2 * scale)
    g1 = scale * _sum_sin_squared_over(c1, theta)
    g2 = scale * _sum_sin_squared_over(c2, theta)
    return np.real((g1 - g2) / (rho2 - rho1)) / D22


def navier_static_compliance(length_x, length_y, D11, D22, D12, D66, impact_point,
                             terms: int = _NAVIER_STATIC_TERMS) -> float:
    """Classical point compliance 1/K_st [m/N] of a simply supported orthotropic plate.

    Sums the Navier double series of PHYSICS.md 3.3,
    ``Σ_m Σ_n (4/(ab)) s_m(x0)² s_n(y0)² / (π⁴[D11 (m/a)⁴ + 2(D12+2D66)(m/a)²(n/b)² + D22 (n/b)⁴])``,
    with the inner series over n in closed form (hyperbolic functions, in the manner of
    Timoshenko & Woinowsky-Krieger, *Theory of Plates and Shells*, §30, extended to
    orthotropy by partial fractions) and the outer series over m summed to ``terms``
    terms plus an asymptotic tail ``½ κ Σ_{m>M} m⁻³`` (the inner sum behaves as
    ``κ/m³``). Relative accuracy ≈ 1e-11 for the default ``terms`` at interior points
    (≈ 1e-10 close to a corner; ≲ 5e-11 within
    ``|H² − D11 D22| ≈ 1e-10 D11 D22`` of isotropy).

    Parameters
    ----------
    length_x, length_y : float
        Plate sides a, b [m].
    D11, D22, D12, D66 : float
        Bending stiffnesses [N·m].
    impact_point : tuple of float
        Load and observation point (x0, y0) [m], inside the plate.
    terms : int, optional
        Terms of the outer series.

    Returns
    -------
    float
        Static compliance [m/N]. Isotropic square plate, centre: ``0.0116008 a²/D``.
    """
    a, b = float(length_x), float(length_y)
    x0, y0 = (float(v) for v in impact_point)
    H = D12 + 2.0 * D66
    m = np.arange(1, int(terms) + 1, dtype=float)
    p = m * np.pi / a
    inner = _inner_series(p, b, y0, D11, D22, H)
    weights = _sin_pi(m * x0 / a) ** 2
    total = math.fsum(weights * inner)
    # tail: inner ≈ κ/m³ and s_m² averages to ½
    kappa = inner[-1] * m[-1] ** 3
    tail = 0.5 * kappa * float(scipy.special.zeta(3.0, m[-1] + 1.0))
    return 4.0 / (a * b) * (total + tail)


# ---------------------------------------------------------------------------------
# The plate
# ---------------------------------------------------------------------------------
@dataclass(frozen=True)
class Plate(Target):
    """Rectangular, specially orthotropic plate struck by a sphere (SI units).

    Parameters
    ----------
    length_x, length_y : float
        Plate sides a (along x) and b (along y) [m], > 0.
    thickness : float
        Plate thickness h [m], > 0 (descriptive; the mechanics uses the stiffnesses).
    D11, D22, D12, D66 : float
        Bending stiffnesses [N·m]: D11, D22, D66 > 0 and ``|D12| < sqrt(D11 D22)``
        (positive-definite bending energy) with ``D12 + 2 D66 > 0``.
    A44, A55 : float
        Transverse shear stiffnesses (yz and xz) [N/m], > 0, before the shear correction.
    mass_per_area : float
        ρh [kg/m²], > 0.
    rotary_inertia_per_area : float
        ρh³/12 [kg], ≥ 0 (> 0 for Mindlin; unused by Kirchhoff).
    theory : {"kirchhoff", "mindlin"}, optional
        Plate theory. Kirchhoff: no shear deformation, no rotary inertia. Mindlin:
        first-order shear deformation with rotary inertia (SSSS only).
    edges : str, optional
        Four characters from {"S", "C", "F"} for the edges x = 0, y = 0, x = a, y = b
        (simply supported, clamped, free), e.g. "SSSS", "CCCC", "CSCS", "CFFF".
        Edge codes that leave rigid-body freedom (no "C" and at most one "S") are rejected.
    impact_point : tuple of float, optional
        Impact point (x0, y0) [m], strictly inside the plate; default the centre.
    shear_correction : float, optional
        Mindlin shear correction factor k [-] (default 5/6).
    damping_ratio : float, optional
        Modal viscous damping ratio [-] applied to every mode, in [0, 1) (default 0).

    Notes
    -----
    * SSSS uses Navier (exact), other edges the Kirchhoff Ritz basis of
      :mod:`impactmaps.targets.ritz` (cached, basis size chosen from ``max_frequency``).
    * ``theory="mindlin"`` with edges other than "SSSS" raises ``NotImplementedError``.
    * λ uses the classical static stiffness (:meth:`static_compliance`).
    """

    structure: ClassVar[str] = "plate"

    length_x: float
    length_y: float
    thickness: float
    D11: float  # noqa: N815 (classical lamination theory symbols)
    D22: float  # noqa: N815
    D12: float  # noqa: N815
    D66: float  # noqa: N815
    A44: float  # noqa: N815
    A55: float  # noqa: N815
    mass_per_area: float
    rotary_inertia_per_area: float
    theory: str = "kirchhoff"
    edges: str = "SSSS"
    impact_point: tuple | None = None
    shear_correction: float = 5.0 / 6.0
    damping_ratio: float = 0.0

    def __post_init__(self):
        require_positive("length_x", self.length_x, "m")
        require_positive("length_y", self.length_y, "m")
        require_positive("thickness", self.thickness, "m")
        require_positive("D11", self.D11, "N·m")
        require_positive("D22", self.D22, "N·m")
        require_positive("D66", self.D66, "N·m")
        bound = math.sqrt(self.D11 * self.D22)
        require_in_range("D12", self.D12, max(-bound, -2.0 * self.D66), bound,
                         low_inclusive=False, high_inclusive=False, unit="N·m")
        require_positive("A44", self.A44, "N/m")
        require_positive("A55", self.A55, "N/m")
        require_positive("mass_per_area", self.mass_per_area, "kg/m²")
        require_choice("theory", self.theory, PLATE_THEORIES)
        if self.theory == "mindlin":
            require_positive("rotary_inertia_per_area", self.rotary_inertia_per_area, "kg")
        else:
            require_nonnegative("rotary_inertia_per_area", self.rotary_inertia_per_area, "kg")
        if not (isinstance(self.edges, str) and len(self.edges) == 4
                and all(c in ritz.EDGE_CODES for c in self.edges)):
            raise ValueError(
                f"edges = {self.edges!r} is not known: valid values are 4-character codes of "
                "'S' (simply supported), 'C' (clamped), 'F' (free) for the edges "
                "(x=0, y=0, x=a, y=b), e.g. 'SSSS', 'CCCC', 'CSCS'"
            )
        if ritz.has_rigid_body_freedom(self.edges):
            raise ValueError(
                f"edges = {self.edges!r} is not supported: the plate can move as a rigid body "
                "(no clamped edge and at most one simply supported edge); its static point "
                "stiffness is zero"
            )
        if self.theory == "mindlin" and self.edges != "SSSS":
            raise NotImplementedError(
                f"theory = 'mindlin' is implemented for edges = 'SSSS' only (got {self.edges!r}); "
                "use theory = 'kirchhoff' for other edges"
            )
        require_in_range("shear_correction", self.shear_correction, 0.0, math.inf,
                         low_inclusive=False)
        require_in_range("damping_ratio", self.damping_ratio, 0.0, 1.0, high_inclusive=False)
        point = (0.5 * self.length_x, 0.5 * self.length_y) if self.impact_point is None else self.impact_point
        try:
            x0, y0 = (float(v) for v in point)
        except (TypeError, ValueError):
            raise ValueError(f"impact_point = {self.impact_point!r} is invalid: must have 2 entries (x0, y0) [m]") from None
        require_in_range("impact_point[0] (x0)", x0, 0.0, self.length_x,
                         low_inclusive=False, high_inclusive=False, unit="m")
        require_in_range("impact_point[1] (y0)", y0, 0.0, self.length_y,
                         low_inclusive=False, high_inclusive=False, unit="m")
        object.__setattr__(self, "impact_point", (x0, y0))
        for name in ("length_x", "length_y", "thickness", "D11", "D22", "D12", "D66", "A44", "A55",
                     "mass_per_area", "rotary_inertia_per_area", "shear_correction", "damping_ratio"):
            object.__setattr__(self, name, float(getattr(self, name)))  # hashable plain numbers

    # -- constructors -------------------------------------------------------------
    @classmethod
    def isotropic(cls, length_x, length_y, thickness, material, **kwargs) -> "Plate":
        """Isotropic plate from a material with ``youngs_modulus`` [Pa], ``poisson_ratio``
        [-] and ``density`` [kg/m³].

        ``D = E h³/(12(1−ν²))``, ``D11 = D22 = D``, ``D12 = ν D``, ``D66 = (1−ν) D/2``,
        ``A44 = A55 = G h`` with ``G = E/(2(1+ν))``, ``ρh``, ``ρh³/12``. Remaining keyword
        arguments go to :class:`Plate`.
        """
        require_positive("thickness", thickness, "m")
        E = float(material.youngs_modulus)
        nu = float(material.poisson_ratio)
        rho = float(material.density)
        require_positive("youngs_modulus", E, "Pa")
        require_in_range("poisson_ratio", nu, -1.0, 0.5, low_inclusive=False, high_inclusive=False)
        require_positive("density", rho, "kg/m³")
        h = float(thickness)
        D = E * h**3 / (12.0 * (1.0 - nu**2))
        G = E / (2.0 * (1.0 + nu))
        return cls(length_x=length_x, length_y=length_y, thickness=h, D11=D, D22=D,
                   D12=nu * D, D66=0.5 * (1.0 - nu) * D, A44=G * h, A55=G * h,
                   mass_per_area=rho * h, rotary_inertia_per_area=rho * h**3 / 12.0, **kwargs)

    @classmethod
    def from_laminate(cls, length_x, length_y, laminate, **kwargs) -> "Plate":
        """Plate from a laminate (e.g. :class:`impactmaps.materials.Laminate`).

        Uses the laminate's ``D11, D22, D12, D66`` [N·m], ``A44, A55`` [N/m],
        ``mass_per_area`` [kg/m²], ``rotary_inertia_per_area`` [kg] and ``thickness`` [m].
        Bending–twisting (D16, D26) and extension–bending (B) couplings are ignored by
        the specially orthotropic model; a warning is issued when the laminate reports
        ``is_specially_orthotropic = False``.
        """
        if not bool(getattr(laminate, "is_specially_orthotropic", True)):
            warnings.warn(
                "laminate is not specially orthotropic: D16, D26 and B couplings are ignored "
                "by the plate model", stacklevel=2)
        return cls(length_x=length_x, length_y=length_y, thickness=float(laminate.thickness),
                   D11=float(laminate.D11), D22=float(laminate.D22), D12=float(laminate.D12),
                   D66=float(laminate.D66), A44=float(laminate.A44), A55=float(laminate.A55),
                   mass_per_area=float(laminate.mass_per_area),
                   rotary_inertia_per_area=float(laminate.rotary_inertia_per_area), **kwargs)

    # -- simple properties ----------------------------------------------------------
    @property
    def effective_bending_stiffness(self) -> float:
        """D* = ½(D12 + 2 D66 + sqrt(D11 D22)) [N·m] (seed 001 eq 31)."""
        return float(effective_plate_stiffness(self.D11, self.D22, self.D12, self.D66))

    @property
    def aspect_ratio(self) -> float:
        """a/b [-]."""
        return self.length_x / self.length_y

    @property
    def mass(self) -> float:
        """Total plate mass ρh a b [kg]."""
        return self.mass_per_area * self.length_x * self.length_y

    def distance_to_nearest_edge(self) -> float:
        """Shortest distance [m] from the impact point to an edge (first wave return)."""
        x0, y0 = self.impact_point
        return min(x0, self.length_x - x0, y0, self.length_y - y0)

    def reflection_time(self, contact_frequency):
        """Normalised time ω d²/c [-] of the first wave return to the impact point.

        ``contact_frequency`` ω [rad/s] (may be an array); d the distance [m] to the
        nearest edge (:meth:`distance_to_nearest_edge`), ``c = sqrt(D*/ρh)`` [m²/s].
        """
        distance = self.distance_to_nearest_edge()
        speed = math.sqrt(self.effective_bending_stiffness / self.mass_per_area)
        return np.asarray(contact_frequency) * distance**2 / speed

    @classmethod
    def infinite_structure_peak(cls, loss_factor):
        """Normalised peak force on the infinite plate F̄∞(ζ) [-] (seed 001 eq 32).

        From :func:`impactmaps.solvers.asymptotes.infinite_plate_peak`; ``loss_factor``
        ζ [-] scalar or array.
        """
        return np.asarray(asymptotes.infinite_plate_peak(np.asarray(loss_factor, dtype=float)),
                          dtype=float)

    @classmethod
    def infinite_structure_impact(cls, loss_factor: float) -> InfiniteImpact:
        """Impact on the infinite plate at loss factor ζ [-] (normalised; :class:`InfiniteImpact`).

        On the infinite plate the plate velocity under the load is proportional to the
        force, zero at separation, so the rebound velocity is the indentation rate then.
        """
        contact = asymptotes.infinite_plate_contact_time(loss_factor)
        rebound = (asymptotes.infinite_plate_indentation_rate(contact, loss_factor)
                   if np.isfinite(contact) else np.nan)
        return InfiniteImpact(asymptotes.infinite_plate_peak(loss_factor),
                              asymptotes.infinite_plate_peak_time(loss_factor), contact, rebound)

    def fundamental_frequency(self) -> float:
        """Lowest natural frequency ω_1 [rad/s] of the plate (any theory and edges)."""
        if self.edges == "SSSS":
            return float(self._navier_frequencies(np.array([1.0]), np.array([1.0]))[0])
        args = (self.length_x, self.length_y, self.D11, self.D22, self.D12, self.D66, self.mass_per_area)
        n_x, n_y, _, _ = ritz.ritz_basis_size(0.0, *args)
        return float(ritz.solve_ritz_plate(*args, self.edges, n_x, n_y).frequencies[0])

    # -- Target interface -------------------------------------------------------------
    def static_compliance(self) -> float:
        """Classical (shear-rigid) static point compliance 1/K_st [m/N] at the impact point.

        SSSS: Navier series with the inner sum in closed form
        (:func:`navier_static_compliance`, ≈ 1e-11 relative). Other edges: Ritz static
        solve with :data:`STATIC_RITZ_FUNCTIONS` functions per direction plus a
        singularity correction, ``C = C_Ritz(edges) + [C_Navier(SSSS) − C_Ritz(SSSS)]``
        (same stiffnesses, point and basis size): the slowly converging part of a Ritz
        point compliance comes from the local ``r² ln r`` singularity under the load,
        which does not depend on the edges, so it cancels in the bracket. Measured
        accuracy ≈ 2e-4 relative (clamped square plate, centre: 0.0056130 a²/D against
        0.0056120 extrapolated) and ≲ 5e-4 in the cases tried (orthotropic, off-centre,
        CFCF/CCSS/CFFF), against 2e-3 – 5e-3 for the plain Ritz value. Used for λ also when
        ``theory="mindlin"`` (the Mindlin point-load deflection is infinite).
        """
        return classical_static_compliance(self.length_x, self.length_y, self.D11, self.D22,
                                           self.D12, self.D66, self.edges, self.impact_point)

    def loss_factor(self, impactor_mass, contact_stiffness):
        """Plate loss factor ζ = (1/16) sqrt(m_i K/(ρh D*)) [-] (seed 001 eq 34).

        Parameters
        ----------
        impactor_mass : float or array_like
            m_i [kg].
        contact_stiffness : float or array_like
            Linear contact stiffness K [N/m].
        """
        return loss_factor_plate(impactor_mass, contact_stiffness, self.mass_per_area,
                                 self.effective_bending_stiffness)

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        """Impactor mass m_i = 256 ζ² ρh D*/K [kg] giving ``loss_factor`` ζ.

        Parameters
        ----------
        loss_factor : float or array_like
            ζ [-].
        contact_stiffness : float or array_like
            Linear contact stiffness K [N/m].
        """
        return impactor_mass_for_plate(loss_factor, contact_stiffness, self.mass_per_area,
                                       self.effective_bending_stiffness)

    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """All modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``).

        SSSS, Kirchhoff: ``ω_mn² = π⁴[D11 (m/a)⁴ + 2(D12+2D66)(m/a)²(n/b)² + D22 (n/b)⁴]/ρh``,
        ``φ = (2/sqrt(ρh a b)) s_m(x0) s_n(y0)``.

        SSSS, Mindlin: for each (m, n) the 3×3 problem ``(K − ω² M)[W, X, Y] = 0`` with
        ``w = W s_m s_n``, ``ψx = X c_m s_n``, ``ψy = Y s_m c_n``, ``p = mπ/a``,
        ``q = nπ/b``::

            K = [[kA55 p² + kA44 q², kA55 p,                  kA44 q                 ],
                 [kA55 p,            D11 p² + D66 q² + kA55, (D12 + D66) p q        ],
                 [kA44 q,            (D12 + D66) p q,        D66 p² + D22 q² + kA44 ]]
            M = diag(ρh, ρh³/12, ρh³/12)

        Only the lowest (flexural) branch is kept. It is found with ``numpy.linalg.eigvalsh``
        on the stacked, mass-scaled matrices and then polished by safeguarded Newton iteration on
        the condensed scalar equation ``g·S C⁻¹ (B − λI) g − λρh = 0`` (``g = (p, q)``,
        ``S = diag(kA55, kA44)``, ``B`` the 2×2 bending block, ``C = B + S − λI``, ``I``
        the rotary inertia), which is free of the cancellation that limits ``eigh`` on
        thin plates (condition ~ (a/h)⁴). The mode is normalised with
        ``(ρh W² + ρh³/12 (X² + Y²)) ab/4 = 1`` and ``φ = W s_m(x0) s_n(y0)``.

        The two thickness-shear branches per (m, n) are omitted: their frequencies lie
        above ``sqrt(k min(A44, A55)/(ρh³/12))`` (the thickness-shear cut-off, far above
        the contact frequencies of interest; a warning is issued when ``max_frequency``
        exceeds it) and a transverse point load hardly excites them. Quantitatively, for
        an isotropic plate (ν = 0.3) with h/a = 0.1 struck at the centre, the static
        compliance ``W²/ω²`` carried by the two shear branches is 1.2e-5 of that of the
        flexural branch for (m, n) = (1, 1) and at most 1.2% over all odd m, n ≤ 19
        (largest where the half-wavelength approaches the thickness, at the limit of
        Mindlin theory itself); checked in ``tests/test_plate_targets.py``.

        Residual compliance: Kirchhoff — exact classical static compliance minus the
        retained ``Σ φ²/ω²``. Mindlin — the Mindlin point-load static deflection is
        infinite, so the residual is defined as the *classical* compliance of the
        dropped half-wave pairs: classical static compliance minus the classical
        (Kirchhoff) modal compliance ``Σ φ_K²/ω_K²`` of the retained (m, n). It is
        finite, ≥ 0, and tends to zero as the cut-off grows; it omits the (log-divergent)
        shear flexibility of the dropped modes.

        Other edges (Kirchhoff Ritz): all Ritz modes with ω ≤ ``max_frequency`` that the
        basis resolves; residual = Ritz static compliance (:meth:`static_compliance`)
        minus the retained modal compliance. The basis size follows
        :func:`impactmaps.targets.ritz.ritz_basis_size`; when ``max_frequency`` exceeds
        what the largest allowed basis resolves, a warning is issued and the
        unresolved modes are represented by the residual compliance only.

        Parameters
        ----------
        max_frequency : float
            Cut-off frequency [rad/s], ≥ 0.
        min_modes : int, optional
            Minimum number of modes returned (the lowest ones), ≥ 1.

        Returns
        -------
        ModalBasis
        """
        return _plate_modes(self, *_checked_request(max_frequency, min_modes))[0]

    def mode_shapes(self, points, max_frequency: float, min_modes: int = 1) -> np.ndarray:
        """Mass-normalised transverse mode shapes w_j at ``points`` [kg^-1/2].

        Parameters
        ----------
        points : array_like, shape (n_points, 2)
            Points (x, y) [m] inside or on the plate.
        max_frequency, min_modes
            As in :meth:`modes`; the columns are the same modes, in the same order.

        Returns
        -------
        ndarray, shape (n_points, n_modes)
            Deflection of each mass-normalised mode (for Mindlin, the w component).
        """
        points = np.atleast_2d(np.asarray(points, dtype=float))
        if points.ndim != 2 or points.shape[1] != 2:
            raise ValueError(f"points must have shape (n_points, 2), got {points.shape}")
        require_in_range("points x", points[:, 0], 0.0, self.length_x, unit="m")
        require_in_range("points y", points[:, 1], 0.0, self.length_y, unit="m")
        return _plate_modes(self, *_checked_request(max_frequency, min_modes))[1](points)

    # -- implementation -----------------------------------------------------------------
    # Navier ------------------------------------------------------------------------
    def _kirchhoff_eigenvalues(self, m, n):
        """ω² [rad²/s²] of the classical SSSS plate for half-wave numbers m, n."""
        p2 = (np.pi * m / self.length_x) ** 2
        q2 = (np.pi * n / self.length_y) ** 2
        H = self.D12 + 2.0 * self.D66
        return (self.D11 * p2**2 + 2.0 * H * p2 * q2 + self.D22 * q2**2) / self.mass_per_area

    def _mindlin_blocks(self, p, q):
        """Bending block B (…, 2, 2) and shear stiffnesses kA55, kA44."""
        B = np.empty(p.shape + (2, 2))
        B[..., 0, 0] = self.D11 * p**2 + self.D66 * q**2
        B[..., 1, 1] = self.D66 * p**2 + self.D22 * q**2
        B[..., 0, 1] = B[..., 1, 0] = (self.D12 + self.D66) * p * q
        return B, self.shear_correction * self.A55, self.shear_correction * self.A44

    def _mindlin_matrices(self, m, n):
        """Stacked 3×3 stiffness matrices K (…, 3, 3) and the mass diagonal (3,)."""
        p = np.pi * np.asarray(m, dtype=float) / self.length_x
        q = np.pi * np.asarray(n, dtype=float) / self.length_y
        B, s55, s44 = self._mindlin_blocks(p, q)
        K = np.zeros(p.shape + (3, 3))
        K[..., 0, 0] = s55 * p**2 + s44 * q**2
        K[..., 0, 1] = K[..., 1, 0] = s55 * p
        K[..., 0, 2] = K[..., 2, 0] = s44 * q
        K[..., 1:, 1:] = B
        K[..., 1, 1] += s55
        K[..., 2, 2] += s44
        mass = np.array([self.mass_per_area, self.rotary_inertia_per_area, self.rotary_inertia_per_area])
        return K, mass

    def _mindlin_flexural(self, m, n):
        """Flexural Mindlin branch: ω (…,) and the normalised amplitude W (…,)."""
        m = np.asarray(m, dtype=float)
        n = np.asarray(n, dtype=float)
        p = np.pi * m / self.length_x
        q = np.pi * n / self.length_y
        B, s55, s44 = self._mindlin_blocks(p, q)
        rho_h, inertia = self.mass_per_area, self.rotary_inertia_per_area
        K, mass = self._mindlin_matrices(m, n)
        inv_sqrt = 1.0 / np.sqrt(mass)
        estimate = np.linalg.eigvalsh(K * inv_sqrt[:, None] * inv_sqrt[None, :])[..., 0]
        # Kirchhoff with rotary inertia: an upper bound (ψ = −∇w is admissible)
        upper = (self._kirchhoff_eigenvalues(m, n) * rho_h) / (rho_h + inertia * (p**2 + q**2))
        # lowest eigenvalue of (B + S)/I: the pole of the condensed equation
        d0 = B[..., 0, 0] + s55
        d1 = B[..., 1, 1] + s44
        pole = 0.5 * (d0 + d1 - np.hypot(d0 - d1, 2.0 * B[..., 0, 1])) / inertia
        low = np.zeros_like(upper)
        high = np.minimum(upper, pole * (1.0 - 1e-12))
        lam = np.where((estimate > 0) & (estimate < high), estimate, 0.5 * high)
        sg0, sg1 = s55 * p, s44 * q

        def condensed(lam):
            c00 = B[..., 0, 0] + s55 - lam * inertia
            c11 = B[..., 1, 1] + s44 - lam * inertia
            c01 = B[..., 0, 1]
            det = c00 * c11 - c01**2
            u0 = (c11 * sg0 - c01 * sg1) / det
            u1 = (c00 * sg1 - c01 * sg0) / det
            bg0 = (B[..., 0, 0] - lam * inertia) * p + B[..., 0, 1] * q
            bg1 = B[..., 1, 0] * p + (B[..., 1, 1] - lam * inertia) * q
            value = u0 * bg0 + u1 * bg1 - lam * rho_h
            slope = -rho_h - inertia * (u0**2 + u1**2)
            return value, slope, u0, u1

        # safeguarded Newton (f decreasing and concave on (0, pole), root bracketed)
        for _ in range(200):
            value, slope, _, _ = condensed(lam)
            low = np.where(value > 0, lam, low)
            high = np.where(value <= 0, lam, high)
            new = lam - value / slope
            outside = ~((new > low) & (new < high)) & (value != 0)
            new = np.where(outside, 0.5 * (low + high), new)
            done = np.abs(new - lam) <= 2e-15 * np.abs(lam)
            lam = new
            if np.all(done):
                break
        else:
            warnings.warn("Mindlin flexural frequencies: the Newton polish did not converge to "
                          "machine precision", RuntimeWarning, stacklevel=3)
        _, _, u0, u1 = condensed(lam)
        amplitude = 2.0 / np.sqrt(self.length_x * self.length_y * (rho_h + inertia * (u0**2 + u1**2)))
        return np.sqrt(lam), amplitude

    def _navier_frequencies(self, m, n):
        if self.theory == "kirchhoff":
            return np.sqrt(self._kirchhoff_eigenvalues(np.asarray(m, float), np.asarray(n, float)))
        return self._mindlin_flexural(m, n)[0]

    def _navier_pairs(self, max_frequency):
        """All (m, n) with ω_mn ≤ max_frequency, as two int arrays.

        Relies on ω_mn increasing in m and in n (true for D12 + 2D66 > 0; checked against
        brute-force enumeration in the tests): the largest m at n = 1 and then, for every
        m at once, the largest n are found by vectorised doubling and bisection.
        """
        def frequency(m, n):
            return self._navier_frequencies(np.asarray(m, float), np.asarray(n, float))

        if frequency(1, 1) > max_frequency:
            return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
        m_count = int(_last_index_within(lambda k: frequency(k, np.ones_like(k)), 1, max_frequency)[0])
        m_values = np.arange(1, m_count + 1, dtype=np.int64)
        n_counts = _last_index_within(lambda k: frequency(m_values, k), m_count, max_frequency)
        m_pairs = np.repeat(m_values, n_counts)
        offsets = np.repeat(np.cumsum(n_counts) - n_counts, n_counts)
        n_pairs = np.arange(m_pairs.size, dtype=np.int64) - offsets + 1
        return m_pairs, n_pairs

    def _navier_modes(self, max_frequency, min_modes):
        if self.theory == "mindlin":
            cutoff = math.sqrt(self.shear_correction * min(self.A44, self.A55)
                               / self.rotary_inertia_per_area)
            if max_frequency > cutoff:
                warnings.warn(
                    f"max_frequency = {max_frequency:.6g} rad/s exceeds the thickness-shear "
                    f"cut-off {cutoff:.6g} rad/s: the Mindlin thickness-shear branches, which "
                    "are omitted, have modes below the cut-off frequency", stacklevel=4)
        cutoff_frequency = max_frequency
        m, n = self._navier_pairs(cutoff_frequency)
        while m.size < min_modes:
            cutoff_frequency = max(2.0 * cutoff_frequency, 1.5 * float(self._navier_frequencies(1, 1)))
            m, n = self._navier_pairs(cutoff_frequency)
        if self.theory == "kirchhoff":
            omega = np.sqrt(self._kirchhoff_eigenvalues(m.astype(float), n.astype(float)))
            amplitude = np.full(omega.shape, 2.0 / math.sqrt(self.mass))
        else:
            omega, amplitude = self._mindlin_flexural(m, n)
        order = np.lexsort((n, m, omega))
        keep = order[: max(int(np.sum(omega <= max_frequency)), min_modes)]
        m, n, omega, amplitude = m[keep], n[keep], omega[keep], amplitude[keep]
        x0, y0 = self.impact_point
        a, b = self.length_x, self.length_y
        participation = amplitude * _sin_pi(m * x0 / a) * _sin_pi(n * y0 / b)

        retained = None  # Kirchhoff: Σ φ²/ω² of the modes themselves
        if self.theory == "mindlin":
            classical = (4.0 / self.mass) * (_sin_pi(m * x0 / a) * _sin_pi(n * y0 / b)) ** 2
            retained = float(np.sum(classical / self._kirchhoff_eigenvalues(m.astype(float), n.astype(float))))
        basis = ModalBasis.from_modes(omega, participation, self.static_compliance(),
                                      self._damping_ratios(omega), retained_compliance=retained)

        def shape_function(points):
            return amplitude[None, :] * _sin_pi(points[:, :1] * m[None, :] / a) * _sin_pi(
                points[:, 1:] * n[None, :] / b)

        return basis, shape_function

    # Ritz ----------------------------------------------------------------------------
    def _ritz_modes(self, max_frequency, min_modes):
        args = (self.length_x, self.length_y, self.D11, self.D22, self.D12, self.D66, self.mass_per_area)
        sizing_frequency = max_frequency
        while True:
            n_x, n_y, required_x, required_y = ritz.ritz_basis_size(sizing_frequency, *args)
            solution = ritz.solve_ritz_plate(*args, self.edges, n_x, n_y)
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
        participation = solution.mode_shapes(np.array([self.impact_point]), count)[0]
        basis = ModalBasis.from_modes(omega, participation, self.static_compliance(),
                                      self._damping_ratios(omega))

        def shape_function(points):
            return solution.mode_shapes(points, count)

        return basis, shape_function

    def _damping_ratios(self, frequencies):
        return np.full(frequencies.shape, float(self.damping_ratio))


def _last_index_within(frequency_of_index, size, limit):
    """Largest k ≥ 1 (array of ``size``) with ``frequency_of_index(k) ≤ limit``.

    ``frequency_of_index`` maps an int array of shape (size,) to frequencies and must be
    increasing in k, with ``frequency_of_index(1) ≤ limit``.
    """
    low = np.ones(size, dtype=np.int64)
    high = np.full(size, 2, dtype=np.int64)
    while True:
        inside = frequency_of_index(high) <= limit
        if not np.any(inside):
            break
        low = np.where(inside, high, low)
        high = np.where(inside, 2 * high, high)
    while np.any(high - low > 1):
        middle = (low + high) // 2
        inside = frequency_of_index(middle) <= limit
        low = np.where(inside, middle, low)
        high = np.where(inside, high, middle)
    return low


def _checked_request(max_frequency, min_modes) -> tuple[float, int]:
    """(cut-off [rad/s], mode count) of a request for modes, validated."""
    require_nonnegative("max_frequency", max_frequency, "rad/s")
    require_in_range("min_modes", min_modes, 1, math.inf)
    if int(min_modes) != min_modes:
        raise ValueError(f"min_modes = {min_modes!r} is invalid: must be an integer >= 1")
    return float(max_frequency), int(min_modes)


@functools.lru_cache(maxsize=8)
def _plate_modes(plate: Plate, max_frequency: float, min_modes: int):
    """(:class:`ModalBasis`, mode-shape function of points) of :meth:`Plate.modes` (cached)."""
    if plate.edges == "SSSS":
        return plate._navier_modes(max_frequency, min_modes)
    return plate._ritz_modes(max_frequency, min_modes)


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
    ritz_edges = ritz.ritz_static_compliance(*args, edges, impact_point, n, n)
    ritz_ssss = ritz.ritz_static_compliance(*args, "SSSS", impact_point, n, n)
    return ritz_edges + (navier - ritz_ssss)
