"""Rectangular plates (Kirchhoff or Mindlin, isotropic or symmetric laminates) as impact targets.

Specially orthotropic SSSS plates use the Navier solution (:mod:`~impactmaps.targets.plates.plate_navier`,
static series :mod:`~impactmaps.targets.plates.plate_static`); Kirchhoff plates on other S/C/F edges the
Ritz basis of :mod:`~impactmaps.targets.plates.ritz`; Mindlin plates on other edges and plates with
D16, D26 or A45 the general basis (:mod:`~impactmaps.targets.plates.plate_any_edges`). This module holds
the :class:`Plate` dataclass, its constructors and the choice (docs/plates_any_edges.rst).

Conventions: the plate occupies ``0 ≤ x ≤ a``, ``0 ≤ y ≤ b``; the edge code lists the
edges x = 0, y = 0, x = a, y = b in that order; A55 is the xz and A44 the yz transverse
shear stiffness. The static point stiffness (for λ) is always the classical (shear-rigid)
value: a Mindlin point-load deflection diverges logarithmically.
"""
from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from ..._checks import (
    require_choice,
    require_in_range,
    require_isotropic_material,
    require_nonnegative,
    require_positive,
    require_positive_fields,
)
from ...dimensionless import (
    effective_plate_stiffness,
    impactor_mass_for_plate,
    loss_factor_plate,
)
from ...closed_forms import asymptotes
from . import plate_any_edges, plate_navier, ritz
from ..base import InfiniteImpact, ModalBasis, Target
from ..options import PLATE_THEORIES, impact_coordinate_range
from .plate_ritz import classical_static_compliance, ritz_plate_modes

__all__ = ["Plate"]



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
        first-order shear deformation with rotary inertia (any edges).
    edges : str, optional
        Four characters from {"S", "C", "F"} for the edges x = 0, y = 0, x = a, y = b
        (simply supported, clamped, free), e.g. "SSSS", "CCCC", "CSCS", "CFFF".
        Edge codes that leave rigid-body freedom (no "C" and at most one "S") are rejected.
    impact_point : tuple of float, optional
        Impact point (x0, y0) [m], strictly inside the plate and at least 1e-6 of the side
        from a supported (S or C) edge
        (:data:`~impactmaps.targets.options.MIN_SUPPORT_DISTANCE`); default the centre.
    shear_correction : float, optional
        Mindlin shear correction factor k [-] (default 5/6).
    damping_ratio : float, optional
        Modal viscous damping ratio [-] applied to every mode, in [0, 1) (default 0).

    Notes
    -----
    * SSSS specially orthotropic uses Navier (exact); other plates a Ritz basis (cached,
      sized from ``max_frequency``): :meth:`modes`.
    * λ uses the classical static stiffness (:meth:`static_compliance`).
    """

    kind: ClassVar[str] = "plate"

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
    D16: float = 0.0  # noqa: N815
    D26: float = 0.0  # noqa: N815
    A45: float = 0.0  # noqa: N815

    def __post_init__(self):
        require_positive_fields(self, {"length_x": "m", "length_y": "m", "thickness": "m",
                                       "D11": "N·m", "D22": "N·m", "D66": "N·m"})
        bound = math.sqrt(self.D11 * self.D22)
        require_in_range("D12", self.D12, max(-bound, -2.0 * self.D66), bound,
                         low_inclusive=False, high_inclusive=False, unit="N·m")
        require_positive("A44", self.A44, "N/m")
        require_positive("A55", self.A55, "N/m")
        plate_any_edges.check_couplings(self)
        require_positive("mass_per_area", self.mass_per_area, "kg/m²")
        require_choice("theory", self.theory, PLATE_THEORIES)
        if self.theory == "mindlin":
            require_positive("rotary_inertia_per_area", self.rotary_inertia_per_area, "kg")
        else:
            require_nonnegative("rotary_inertia_per_area", self.rotary_inertia_per_area, "kg")
        ritz.require_edges(self.edges, self.theory)
        require_in_range("shear_correction", self.shear_correction, 0.0, math.inf,
                         low_inclusive=False)
        require_in_range("damping_ratio", self.damping_ratio, 0.0, 1.0, high_inclusive=False)
        point = (0.5 * self.length_x, 0.5 * self.length_y) if self.impact_point is None else self.impact_point
        try:
            x0, y0 = (float(v) for v in point)
        except (TypeError, ValueError):
            raise ValueError(f"impact_point = {self.impact_point!r} is invalid: must have 2 entries (x0, y0) [m]") from None
        # every edge keeps the point inside, a supported one 1e-6 of the span away
        for label, value, span, low_edge, high_edge in (("impact_point[0] (x0)", x0, self.length_x, 0, 2),
                                                         ("impact_point[1] (y0)", y0, self.length_y, 1, 3)):
            low, high = impact_coordinate_range(span, self.edges[low_edge] != "F", self.edges[high_edge] != "F")
            require_in_range(label, value, low, high, low_inclusive=low > 0.0,
                             high_inclusive=high < span, unit="m")
        object.__setattr__(self, "impact_point", (x0, y0))
        for name in ("length_x", "length_y", "thickness", "D11", "D22", "D12", "D66", "A44", "A55",
                     "mass_per_area", "rotary_inertia_per_area", "shear_correction", "damping_ratio",
                     "D16", "D26", "A45"):
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
        E, nu, rho = require_isotropic_material("material", material)
        h = float(thickness)
        D = E * h**3 / (12.0 * (1.0 - nu**2))
        G = E / (2.0 * (1.0 + nu))
        return cls(length_x=length_x, length_y=length_y, thickness=h, D11=D, D22=D,
                   D12=nu * D, D66=0.5 * (1.0 - nu) * D, A44=G * h, A55=G * h,
                   mass_per_area=rho * h, rotary_inertia_per_area=rho * h**3 / 12.0, **kwargs)

    @classmethod
    def from_laminate(cls, length_x, length_y, laminate, **kwargs) -> "Plate":
        """Plate from a laminate (e.g. :class:`impactmaps.materials.Laminate`).

        Uses the laminate's full bending stiffness (D11, D22, D12, D66, D16, D26) [N·m],
        transverse shear stiffness (A44, A55, A45) [N/m], ``mass_per_area`` [kg/m²],
        ``rotary_inertia_per_area`` [kg] and ``thickness`` [m]. Couplings whose ratio
        (:meth:`~impactmaps.materials.Laminate.coupling_ratios`) is below
        :data:`~impactmaps.materials._common.SPECIALLY_ORTHOTROPIC_RTOL` are round-off and
        set to 0 (a specially orthotropic SSSS laminate keeps its Navier modes).

        Raises
        ------
        ValueError
            For an unsymmetric laminate (extension–bending coupling B ≠ 0): the plate
            model has no membrane displacements, and dropping B would make the plate
            stiffer than it is.
        """
        d16, d26, a45 = plate_any_edges.laminate_couplings(laminate)
        return cls(length_x=length_x, length_y=length_y, thickness=float(laminate.thickness),
                   D11=float(laminate.D11), D22=float(laminate.D22), D12=float(laminate.D12),
                   D66=float(laminate.D66), A44=float(laminate.A44), A55=float(laminate.A55),
                   mass_per_area=float(laminate.mass_per_area),
                   rotary_inertia_per_area=float(laminate.rotary_inertia_per_area),
                   D16=d16, D26=d26, A45=a45, **kwargs)

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

    def distance_to_nearest_support(self) -> float:
        """Shortest distance [m] from the impact point to a clamped or simply supported edge."""
        x0, y0 = self.impact_point
        distances = (x0, y0, self.length_x - x0, self.length_y - y0)
        return min((d for edge, d in zip(self.edges, distances) if edge != "F"), default=math.inf)

    @property
    def section_depth(self) -> float:
        """The plate's thickness h [m]."""
        return self.thickness

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

        From :func:`impactmaps.closed_forms.asymptotes.infinite_plate_peak`; ``loss_factor``
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

    @property
    def bending_stiffness_matrix(self) -> np.ndarray:
        """[[D11, D12, D16], [D12, D22, D26], [D16, D26, D66]] [N·m]."""
        return np.array([[self.D11, self.D12, self.D16], [self.D12, self.D22, self.D26],
                         [self.D16, self.D26, self.D66]])

    @property
    def uses_navier(self) -> bool:
        """True for the specially orthotropic SSSS plate (Navier modes, exact)."""
        return self.edges == "SSSS" and not plate_any_edges.uses_general_basis(self)

    def fundamental_frequency(self) -> float:
        """Lowest natural frequency ω_1 [rad/s] of the plate (any theory and edges)."""
        if plate_any_edges.uses_general_basis(self):
            return float(plate_any_edges.all_modes(self, 1)[0][0])
        if self.edges == "SSSS":
            return float(self._navier_frequencies(np.array([1.0]), np.array([1.0]))[0])
        args = (self.length_x, self.length_y, self.D11, self.D22, self.D12, self.D66, self.mass_per_area)
        n_x, n_y, _, _ = ritz.ritz_basis_size(0.0, *args)
        return float(ritz.solve_ritz_plate(*args, self.edges, n_x, n_y).frequencies[0])

    def mode_table(self, count: int) -> dict:
        """The lowest ``count`` natural frequencies with labels and the basis that gave them:
        ``frequencies_hz`` (ndarray, lowest first) [Hz], ``labels`` (``"(m, n)"`` half-waves
        for a Navier plate, else the index from 1), ``method``, ``basis``,
        ``resolved_frequency_hz`` [Hz] (``inf`` for Navier) and ``resolved`` (every mode
        returned lies below it) (:func:`~impactmaps.targets.plates.plate_any_edges.mode_table`)."""
        return plate_any_edges.mode_table(self, count)

    def natural_frequencies_hz(self, count: int) -> np.ndarray:
        """The lowest ``count`` natural frequencies [Hz] of the plate's bending modes, lowest
        first (any theory, edges and laminate; :meth:`mode_table`). Warns when some are
        above what the largest basis resolves."""
        table = self.mode_table(count)
        if not table["resolved"]:
            warnings.warn(
                f"count = {count}: the largest Ritz basis ({table['basis']}) resolves modes up to "
                f"{table['resolved_frequency_hz']:.6g} Hz only; the frequencies above it "
                f"(and any missing) are not converged", stacklevel=2)
        return table["frequencies_hz"]

    # -- Target interface -------------------------------------------------------------
    def static_compliance(self) -> float:
        """Classical (shear-rigid) static point compliance 1/K_st [m/N] at the impact point.

        SSSS: Navier series with the inner sum in closed form
        (:func:`~impactmaps.targets.plates.plate_static.navier_static_compliance`, ≈ 1e-11 relative). Other edges: Ritz static
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
        if self.D16 != 0.0 or self.D26 != 0.0:
            return plate_any_edges.classical_compliance(self)
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

    def thickness_shear_frequency(self) -> float | None:
        """Mindlin: the thickness-shear cut-off ``sqrt(k min(A44, A55)/(ρh³/12))`` [rad/s]."""
        return (math.sqrt(self.shear_correction * min(self.A44, self.A55) / self.rotary_inertia_per_area)
                if self.theory == "mindlin" else None)

    wave_return_distance = distance_to_nearest_edge  # the nearest edge reflects first

    def flexural_group_velocity(self, angular_frequency):
        """Classical flexural group velocity ``2 (D*/ρh)^(1/4) sqrt(ω)`` [m/s] at ω [rad/s]."""
        return 2.0 * ((self.effective_bending_stiffness / self.mass_per_area) ** 0.25 * math.sqrt(angular_frequency))

    @property
    def supports_contact_patch(self) -> bool:
        """True when :meth:`modes` can spread the load over a contact patch: Navier plates,
        Mindlin plates and plates with D16/D26/A45 (the general basis); not the
        specially orthotropic Kirchhoff Ritz plates."""
        return self.uses_navier or plate_any_edges.uses_general_basis(self)

    def modes(self, max_frequency: float, min_modes: int = 1,
              contact_radius: float | None = None) -> ModalBasis:
        """All modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``), seen from
        the impact point, with the residual compliance of the rest.

        SSSS specially orthotropic: Navier (Kirchhoff closed form; Mindlin the flexural
        branch of the 3×3 problem per (m, n)). Kirchhoff on other edges: the Ritz basis of
        :mod:`~impactmaps.targets.plates.ritz`. Mindlin on other edges, or D16/D26/A45: the general
        basis (:mod:`~impactmaps.targets.plates.plate_any_edges`). A warning when ``max_frequency``
        exceeds what the largest basis resolves (the rest is residual compliance) or, for a
        Mindlin point load, the thickness-shear cut-off. Equations, residuals and measured
        accuracy: docs/physics.rst (Plate targets) and docs/plates_any_edges.rst.

        Parameters
        ----------
        max_frequency : float
            Cut-off frequency [rad/s], ≥ 0.
        min_modes : int, optional
            Minimum number of modes returned (the lowest ones), ≥ 1.
        contact_radius : float, optional
            Radius [m] of the Hertz pressure disc the load is spread over (≥ 0, smaller than
            the distance to the nearest edge; ``None`` or 0: a point load); not on
            specially orthotropic Kirchhoff Ritz plates (:attr:`supports_contact_patch`).

        Returns
        -------
        ModalBasis
        """
        return _plate_modes(self, *_checked_request(max_frequency, min_modes),
                            self._checked_contact_radius(contact_radius))[0]

    def mode_count(self, max_frequency: float, limit: int | None = None) -> int:
        """Number of modes with ω ≤ ``max_frequency`` [rad/s], participating or not.

        SSSS: counted without building them (:func:`plate_navier.navier_mode_count`; a
        lower bound above ``limit`` once the count exceeds it). Other edges: the Ritz
        modes :meth:`modes` resolves (built; the general basis: in its largest basis).
        """
        require_nonnegative("max_frequency", max_frequency, "rad/s")
        if self.uses_navier:
            return plate_navier.navier_mode_count(self, float(max_frequency), limit)
        if plate_any_edges.uses_general_basis(self):  # one eigen-solution for every count
            return plate_any_edges.resolved_count(self, float(max_frequency))
        return super().mode_count(max_frequency, limit)

    def mode_count_bound(self) -> float:
        """An upper bound [-] of every :meth:`mode_count` (:func:`plate_any_edges.mode_count_bound`)."""
        return plate_any_edges.mode_count_bound(self)

    @property
    def bounded_modes(self) -> bool:
        """True for the Ritz plates (all but the Navier ones): a basis of bounded size."""
        return not self.uses_navier

    def resolution_limit(self) -> float:
        """Highest frequency [rad/s] the plate's modes resolve: ``inf`` for SSSS (Navier,
        exact), else what the largest Ritz basis (:data:`ritz.MAX_FUNCTIONS` per direction)
        resolves (:attr:`ritz.RitzPlateSolution.resolved_frequency`)."""
        if self.uses_navier:
            return math.inf
        if plate_any_edges.uses_general_basis(self):
            cap = plate_any_edges.max_functions(self.theory, plate_any_edges.class_groups(self)[0])
            return plate_any_edges.resolved_frequency(self, cap, cap)
        return ritz.largest_resolved_frequency(self.length_x, self.length_y, self.D11, self.D22, self.D12,
                                               self.D66, self.mass_per_area)

    def resolved_mode_count(self) -> int:
        """Modes below :meth:`resolution_limit`: 0 for SSSS (no limit); for a Ritz plate the
        Navier count of its simply supported twin (same stiffnesses), which differs from
        the Ritz count by the edges' boundary-layer term only — counting the Ritz modes
        would take the largest eigen-solution (seconds)."""
        if self.uses_navier:
            return 0
        twin = replace(self, edges="SSSS", D16=0.0, D26=0.0, A45=0.0)
        return plate_navier.navier_mode_count(twin, self.resolution_limit(), None)

    def _checked_contact_radius(self, contact_radius) -> float:
        """``contact_radius`` [m] validated (0.0 for a point load)."""
        if contact_radius is None:
            return 0.0
        require_in_range("contact_radius", contact_radius, 0.0, self.distance_to_nearest_edge(),
                         high_inclusive=False, unit="m")
        if contact_radius > 0.0 and not self.supports_contact_patch:
            raise ValueError(
                f"contact_radius = {contact_radius!r} is not supported with edges = {self.edges!r}: "
                "the contact patch is available on SSSS, Mindlin and coupled (D16/D26) plates; "
                "valid: contact_radius = 0 (point load) on a specially orthotropic Kirchhoff "
                "plate with other edges")
        return float(contact_radius)

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
        return _plate_modes(self, *_checked_request(max_frequency, min_modes), 0.0)[1](points)

    def _navier_frequencies(self, m, n):
        """ω_mn [rad/s] of the SSSS plate (:func:`plate_navier.navier_frequencies`)."""
        return plate_navier.navier_frequencies(self, m, n)


def _checked_request(max_frequency, min_modes) -> tuple[float, int]:
    """(cut-off [rad/s], mode count) of a request for modes, validated."""
    require_nonnegative("max_frequency", max_frequency, "rad/s")
    require_in_range("min_modes", min_modes, 1, math.inf)
    if int(min_modes) != min_modes:
        raise ValueError(f"min_modes = {min_modes!r} is invalid: must be an integer >= 1")
    return float(max_frequency), int(min_modes)


@functools.lru_cache(maxsize=8)
def _plate_modes(plate: Plate, max_frequency: float, min_modes: int, contact_radius: float):
    """(:class:`ModalBasis`, mode-shape function of points) of :meth:`Plate.modes` (cached)."""
    if plate.uses_navier:
        return plate_navier.navier_modes(plate, max_frequency, min_modes, contact_radius)
    if plate_any_edges.uses_general_basis(plate):
        return plate_any_edges.general_plate_modes(plate, max_frequency, min_modes, contact_radius)[:2]
    return ritz_plate_modes(plate, max_frequency, min_modes)
