"""Straight uniform beams (Euler–Bernoulli, Rayleigh, Timoshenko) as impact targets.

A :class:`Beam` is described by its section properties (bD11, kbA55, ρA, ρI; docs/physics_contract.md
§3.2). Modes: closed forms (SS, Euler with any support) or a p-version finite-element model
(:mod:`impactmaps.targets.beams`). A free–free beam's static compliance is its
inertia-relief compliance ``Σ_elastic W_j(x0)²/ω_j²``.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ..._checks import (
    require_choice,
    require_in_range,
    require_isotropic_material,
    require_nonnegative,
    require_positive,
)
from ...dimensionless import impactor_mass_for_beam, loss_factor_beam
from ...closed_forms import infinite_beam
from .beam_euler_modes import classical_euler_modes, euler_roots
from .beam_fe_modes import finite_element_mode_count, finite_element_modes, finite_element_resolution_limit
from .beam_section import ModeSet, largest_wavenumber
from .beam_sine_modes import simply_supported_count, simply_supported_modes
from .beam_static import static_compliance
from ..base import InfiniteImpact, ModalBasis, Target
from .beam_section import BeamSection
from ..options import BEAM_SUPPORTS as SUPPORTS
from ..options import BEAM_THEORIES as THEORIES
from ..options import impact_coordinate_range

__all__ = ["Beam", "MIN_SLENDERNESS"]

#: Smallest length-to-height ratio accepted (beam theory is meaningless below it).
MIN_SLENDERNESS = 2.0


def _scalar(name: str, value, unit: str = "") -> float:
    array = np.asarray(value)
    if array.ndim != 0:
        raise ValueError(f"{name} = {value!r} is invalid: must be a scalar [{unit}]")
    try:
        return float(array)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r} is not a real number [{unit}]") from None


@dataclass(frozen=True)
class Beam(Target):
    """A uniform straight beam struck by a sphere at ``impact_position``.

    Parameters
    ----------
    length : float
        Span L [m], > 0.
    bending_stiffness : float
        bD11 = EI [N·m²], > 0.
    shear_stiffness : float
        k b A55 = kGA [N], > 0 (used by ``"timoshenko"`` only; may be ``math.inf``).
    mass_per_length : float
        m' = ρA [kg/m], > 0.
    rotary_inertia : float
        ρI [kg·m], ≥ 0; > 0 for ``"rayleigh"`` and ``"timoshenko"``.
    theory : {"euler", "rayleigh", "timoshenko"}
        Euler–Bernoulli, Rayleigh (rotary inertia) or Timoshenko (and shear).
    supports : {"ss", "cc", "cs", "cf", "ff"}
        End conditions, x = 0 first (``"cf"``: clamped at x = 0, free at x = L).
    impact_position : float, optional
        x0 [m]; default mid-span; at least 1e-6 L from a supported end, may lie on a
        free end.
    damping_ratio : float, optional
        Modal viscous damping ratio [-] of every elastic mode, in [0, 1); default 0.
    width, height : float, optional
        Section width b and height h [m] when known; ``height`` enables the check L/h ≥ 2.
    """

    kind: ClassVar[str] = "beam"

    length: float
    bending_stiffness: float
    shear_stiffness: float
    mass_per_length: float
    rotary_inertia: float
    theory: str = "timoshenko"
    supports: str = "ss"
    impact_position: float | None = None
    damping_ratio: float = 0.0
    width: float | None = None
    height: float | None = None

    def __post_init__(self):
        require_choice("theory", self.theory, THEORIES)
        require_choice("supports", self.supports, SUPPORTS)
        length = _scalar("length", self.length, "m")
        require_positive("length", length, "m")
        bending = _scalar("bending_stiffness", self.bending_stiffness, "N m^2")
        require_positive("bending_stiffness", bending, "N m^2")
        mass = _scalar("mass_per_length", self.mass_per_length, "kg/m")
        require_positive("mass_per_length", mass, "kg/m")
        shear = _scalar("shear_stiffness", self.shear_stiffness, "N")
        if self.theory == "timoshenko" or not math.isinf(shear):
            require_positive("shear_stiffness", shear, "N")
        elif shear < 0:
            raise ValueError(f"shear_stiffness = {shear!r} is invalid: valid range is (0, inf] [N]")
        rotary = _scalar("rotary_inertia", self.rotary_inertia, "kg m")
        if self.theory == "euler":
            require_nonnegative("rotary_inertia", rotary, "kg m")
        else:
            require_positive("rotary_inertia", rotary, "kg m")
        damping = _scalar("damping_ratio", self.damping_ratio)
        require_in_range("damping_ratio", damping, 0.0, 1.0, high_inclusive=False)
        for name in ("width", "height"):
            value = getattr(self, name)
            if value is not None:
                value = _scalar(name, value, "m")
                require_positive(name, value, "m")
                object.__setattr__(self, name, value)
        if self.height is not None:
            require_in_range("slenderness (length/height)", length / self.height,
                             MIN_SLENDERNESS, math.inf)
        position = 0.5 * length if self.impact_position is None else _scalar(
            "impact_position", self.impact_position, "m")
        low, high = impact_coordinate_range(length, self.supports[0] != "f", self.supports[1] != "f")
        require_in_range("impact_position", position, low, high, unit="m")
        for name, value in (("length", length), ("bending_stiffness", bending),
                            ("shear_stiffness", shear), ("mass_per_length", mass),
                            ("rotary_inertia", rotary), ("damping_ratio", damping),
                            ("impact_position", position)):
            object.__setattr__(self, name, value)

    # -- constructors -----------------------------------------------------------------
    @classmethod
    def rectangular(cls, length, width, height, material, *, theory="timoshenko",
                    supports="ss", impact_position=None, shear_correction=5.0 / 6.0,
                    damping_ratio=0.0) -> "Beam":
        """A solid rectangular beam b × h of an isotropic material (``bD11 = E b h³/12``).

        Parameters
        ----------
        length, width, height : float
            L, b, h [m], > 0; L/h ≥ 2.
        material : object
            With ``youngs_modulus`` [Pa], ``poisson_ratio`` [-] and ``density`` [kg/m³].
        theory, supports, impact_position, damping_ratio
            See :class:`Beam`.
        shear_correction : float
            Shear correction factor k [-], > 0 (5/6 for a rectangle).
        """
        for name, value in (("length", length), ("width", width), ("height", height)):
            require_positive(name, value, "m")
        require_positive("shear_correction", shear_correction)
        youngs, poisson, density = require_isotropic_material("material", material)
        area = float(width) * float(height)
        second_moment = float(width) * float(height) ** 3 / 12.0
        shear_modulus = youngs / (2.0 * (1.0 + poisson))
        return cls(
            length=float(length),
            bending_stiffness=youngs * second_moment,
            shear_stiffness=float(shear_correction) * shear_modulus * area,
            mass_per_length=density * area,
            rotary_inertia=density * second_moment,
            theory=theory,
            supports=supports,
            impact_position=impact_position,
            damping_ratio=damping_ratio,
            width=float(width),
            height=float(height),
        )

    @classmethod
    def from_laminate(cls, length, width, laminate, *, theory="timoshenko", supports="ss",
                      impact_position=None, shear_correction=5.0 / 6.0,
                      damping_ratio=0.0) -> "Beam":
        """A beam of width b cut from a specially orthotropic laminate (``bD11 = b·D11``, seed 001 (16)–(17)).

        Parameters
        ----------
        length, width : float
            L, b [m], > 0.
        laminate : object
            With ``D11`` [N·m], ``A55`` [N/m], ``mass_per_area`` [kg/m²],
            ``rotary_inertia_per_area`` [kg] and ``thickness`` [m].
        theory, supports, impact_position, damping_ratio, shear_correction
            See :meth:`rectangular`.
        """
        require_positive("length", length, "m")
        require_positive("width", width, "m")
        require_positive("shear_correction", shear_correction)
        if hasattr(laminate, "A55"):
            transverse_shear = float(laminate.A55)
        else:
            transverse_shear = float(np.asarray(laminate.transverse_shear_stiffness)[1, 1])
        b = float(width)
        return cls(
            length=float(length),
            bending_stiffness=b * float(laminate.D11),
            shear_stiffness=float(shear_correction) * b * transverse_shear,
            mass_per_length=b * float(laminate.mass_per_area),
            rotary_inertia=b * float(laminate.rotary_inertia_per_area),
            theory=theory,
            supports=supports,
            impact_position=impact_position,
            damping_ratio=damping_ratio,
            width=b,
            height=float(laminate.thickness),
        )

    # -- description ------------------------------------------------------------------
    @property
    def section(self) -> BeamSection:
        """The section as seen by the chosen theory (S = ∞ unless Timoshenko, ρI = 0 for Euler)."""
        return BeamSection.effective(self.length, self.bending_stiffness, self.shear_stiffness,
                                     self.mass_per_length, self.rotary_inertia, self.theory,
                                     self.supports)

    @property
    def slenderness(self) -> float | None:
        """L/h [-], or ``None`` when the height is not known."""
        return None if self.height is None else self.length / self.height

    @property
    def mass(self) -> float:
        """Total mass m' L [kg]."""
        return self.mass_per_length * self.length

    def distance_to_nearest_support(self) -> float:
        """Distance [m] from x0 to the nearest clamped or simply supported end (∞ for ff)."""
        distances = [d for end, d in zip(self.supports, (self.impact_position,
                                                         self.length - self.impact_position))
                     if end != "f"]
        return min(distances) if distances else math.inf

    @property
    def section_depth(self) -> float | None:
        """The section height h [m] in the impact direction, None when not known."""
        return self.height

    def distance_to_nearest_end(self) -> float:
        """Distance [m] from x0 to the nearest end, supported or free."""
        return min(self.impact_position, self.length - self.impact_position)

    def thickness_shear_frequency(self) -> float | None:
        """Thickness-shear cut-off ``sqrt(kGA/(ρI))`` [rad/s] of a Timoshenko beam; None otherwise."""
        if self.theory != "timoshenko":
            return None
        return math.sqrt(self.shear_stiffness / self.rotary_inertia)

    def wave_return_distance(self) -> float:
        """Distance [m] to the nearest end, supported or free (:meth:`distance_to_nearest_end`)."""
        return float(self.distance_to_nearest_end())

    def reflection_time(self, contact_frequency):
        """Normalised time ω d²/c [-] of the first wave return (``contact_frequency`` ω [rad/s],
        d to the nearest support [m], ``c = sqrt(bD11/m')`` [m²/s])."""
        distance = self.distance_to_nearest_support()
        speed = math.sqrt(self.bending_stiffness / self.mass_per_length)
        return np.asarray(contact_frequency) * distance**2 / speed

    @classmethod
    def infinite_structure_peak(cls, loss_factor):
        """Normalised peak force on the infinite beam F̄∞(ζ) [-] at ``loss_factor`` ζ [-] (scalar or array)."""
        zeta = np.asarray(loss_factor, dtype=float)
        unique, inverse = np.unique(zeta, return_inverse=True)
        peaks = np.asarray(infinite_beam.infinite_beam_peak(unique), dtype=float)
        return peaks[inverse].reshape(zeta.shape)

    @classmethod
    def infinite_structure_impact(cls, loss_factor: float) -> InfiniteImpact:
        """Impact on the infinite beam at loss factor ζ [-] (normalised; :class:`InfiniteImpact`)."""
        contact = infinite_beam.infinite_beam_contact_time(loss_factor)
        rebound = (infinite_beam.infinite_beam_impactor_velocity(contact, loss_factor)
                   if np.isfinite(contact) else np.nan)
        return InfiniteImpact(infinite_beam.infinite_beam_peak(loss_factor),
                              infinite_beam.infinite_beam_peak_time(loss_factor), contact, rebound)

    def flexural_wave_speed(self, angular_frequency):
        """Euler flexural phase speed ``c_B = (bD11/m')^{1/4} sqrt(ω)`` [m/s] at ω [rad/s]."""
        require_nonnegative("angular_frequency", angular_frequency, "rad/s")
        omega = np.asarray(angular_frequency, dtype=float)
        speed = (self.bending_stiffness / self.mass_per_length) ** 0.25 * np.sqrt(omega)
        return float(speed) if speed.ndim == 0 else speed

    def flexural_group_velocity(self, angular_frequency):
        """Euler flexural group velocity ``2 c_B`` [m/s] at ω [rad/s] (energy transport)."""
        return 2.0 * self.flexural_wave_speed(angular_frequency)

    # -- modes ------------------------------------------------------------------------
    def mode_set(self, max_frequency: float, min_modes: int = 1) -> ModeSet:
        """All modes with ω ≤ ``max_frequency`` [rad/s] (at least ``min_modes``) as a
        :class:`~impactmaps.targets.beams.beam_section.ModeSet`; rigid-body modes first."""
        require_nonnegative("max_frequency", max_frequency, "rad/s")
        require_in_range("min_modes", min_modes, 0, math.inf)
        if int(min_modes) != min_modes:
            raise ValueError(f"min_modes = {min_modes!r} is invalid: must be an integer")
        section = self.section
        if self.supports == "ss":
            return simply_supported_modes(section, max_frequency, int(min_modes))
        if self.theory == "euler":
            return classical_euler_modes(section, max_frequency, int(min_modes))
        return finite_element_modes(section, max_frequency, int(min_modes))

    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """Modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``) seen from x0, with
        residual compliance; free–free beams include their two rigid-body modes."""
        return _beam_basis(self, float(max_frequency), min_modes)

    def mode_count(self, max_frequency: float, limit: int | None = None) -> int:
        """Number of modes with ω ≤ ``max_frequency`` [rad/s] (rigid-body included), without
        building them; a lower bound above ``limit`` may be returned early."""
        require_nonnegative("max_frequency", max_frequency, "rad/s")
        section, frequency = self.section, float(max_frequency)
        wavenumber = float(largest_wavenumber(section, frequency))
        bound = max(math.floor(wavenumber * self.length / math.pi) - 1, 0)
        if limit is not None and bound > limit:
            return bound
        if self.supports == "ss":
            return simply_supported_count(section, frequency)
        if self.theory == "euler":
            last = int(wavenumber * self.length / math.pi) + 2  # the roots beyond lie above the cut-off
            first = max(last - 3, 1)  # the roots before lie below it
            roots = euler_roots(self.supports, last, first)
            scale = math.sqrt(section.bending_stiffness / (section.mass_per_length * self.length**4))
            rigid = 2 if self.supports == "ff" else 0
            return rigid + first - 1 + int(np.searchsorted(roots**2 * scale, frequency, side="right"))
        return finite_element_mode_count(section, frequency)

    @property
    def bounded_modes(self) -> bool:
        """True when the modes come from a model of bounded size (the finite-element beams)."""
        return self.supports != "ss" and self.theory != "euler"

    def resolution_limit(self) -> float:
        """Highest frequency [rad/s] the beam's modes resolve (``inf`` for the closed forms)."""
        if not self.bounded_modes:
            return math.inf
        return finite_element_resolution_limit(self.section)

    def mode_table(self, count: int) -> dict:
        """The lowest ``count`` natural frequencies [Hz] (``frequencies_hz``), with ``labels``
        (the mode index from 1), ``method``, ``basis``, ``resolved_frequency_hz`` [Hz] and
        ``resolved``, as :meth:`impactmaps.targets.plates.plate.Plate.mode_table`. Rigid-body modes
        (free-free) are listed at 0 Hz."""
        require_in_range("count", count, 1, 100000)
        omega = np.asarray(self.modes(0.0, min_modes=int(count)).frequencies[:int(count)], dtype=float)
        limit = float(self.resolution_limit())
        return {"frequencies_hz": omega / (2.0 * math.pi), "labels": [str(i + 1) for i in range(omega.size)],
                "method": f"{self.theory}, supports {self.supports}",
                "basis": "finite elements" if self.bounded_modes else "closed form",
                "resolved_frequency_hz": limit / (2.0 * math.pi),
                "resolved": bool(omega.size == int(count) and (omega.size == 0 or omega[-1] <= limit))}

    def natural_frequencies_hz(self, count: int) -> np.ndarray:
        """The lowest ``count`` natural frequencies [Hz] of the beam, lowest first."""
        return self.mode_table(count)["frequencies_hz"]

    def mode_shapes(self, points, max_frequency: float, min_modes: int = 1) -> np.ndarray:
        """Mass-normalised deflection shapes W_j at ``points`` [m], shape (n_points, n_modes), of :meth:`modes`."""
        x = np.atleast_1d(np.asarray(points, dtype=float))
        require_in_range("points", x, 0.0, self.length, unit="m")
        return self.mode_set(max_frequency, min_modes).deflection(x)

    def fundamental_frequency(self) -> float:
        """Lowest elastic natural frequency ω_1 [rad/s]."""
        mode_set = self.mode_set(0.0, 3 if self.supports == "ff" else 1)
        return float(mode_set.frequencies[mode_set.frequencies > 0][0])

    # -- statics and dimensionless groups ---------------------------------------------
    def static_compliance(self) -> float:
        """Static point compliance 1/K_st [m/N] at x0 (exact; inertia relief for free–free)."""
        return static_compliance(self.section, self.impact_position)

    def loss_factor(self, impactor_mass, contact_stiffness):
        """Corrected beam loss factor ζ_b [-] for ``impactor_mass`` [kg] and ``contact_stiffness``
        [N/m] (arrays allowed)."""
        return loss_factor_beam(impactor_mass, contact_stiffness, self.mass_per_length,
                                self.bending_stiffness)

    def impactor_mass_for(self, loss_factor, contact_stiffness):
        """Impactor mass ``m_i = m' (4 sqrt(2π) ζ)^{4/3} (bD11/K)^{1/3}`` [kg] (docs/physics_contract.md §4)."""
        return impactor_mass_for_beam(loss_factor, contact_stiffness, self.mass_per_length,
                                      self.bending_stiffness)


@functools.lru_cache(maxsize=8)
def _beam_basis(beam: Beam, max_frequency: float, min_modes) -> ModalBasis:
    """:meth:`Beam.modes` (a pure function of its arguments, cached)."""
    mode_set = beam.mode_set(max_frequency, min_modes)
    frequencies = mode_set.frequencies
    damping = np.where(frequencies > 0, beam.damping_ratio, 0.0)
    return ModalBasis.from_modes(frequencies, mode_set.deflection([beam.impact_position])[0],
                                 beam.static_compliance(), damping)
