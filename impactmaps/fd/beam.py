"""The beam of the finite-difference solver (:class:`FDBeam`) and the run options (:class:`FDSettings`).

A Rayleigh beam with a layered section; equation, sign of the moment term and boundary
conditions: docs/fd_beam.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._checks import (
    require_choice,
    require_finite,
    require_in_range,
    require_nonnegative,
    require_positive,
    require_positive_fields,
)
from ..targets.beams.beam import Beam
from .grid import beam_grid
from .section import LayeredSection, Rectangle
from .wide_section import constraint_parameters

__all__ = ["FDBeam", "FDSettings", "SUPPORT_ENDS", "require_stride"]

_SUPPORTS = ("ss", "cc", "free")
#: Support codes of :class:`impactmaps.targets.beams.beam.Beam` as (left, right) FDBeam ends.
SUPPORT_ENDS = {"ss": ("ss", "ss"), "cc": ("cc", "cc"), "cs": ("cc", "ss"),
                "cf": ("cc", "free"), "ff": ("free", "free")}
#: FDSettings fields that belong to the FDBeam (grid, section, damping).
_BEAM_OPTIONS = ("n_elements", "n_half_layers", "plastic", "hardening_modulus",
                 "damping_per_length", "width_constraint")


# =====================================================================================
# Beam definition
# =====================================================================================
@dataclass(frozen=True)
class FDBeam(Rectangle):
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
        Viscous damping per unit length C [N s/m²] (≥ 0).
    supports : str or (str, str), optional
        ``"ss"`` (default), ``"cc"`` or ``"free"``, for both ends or a (left, right) pair.
    n_elements : int, optional
        Grid intervals N_l along the span (≥ 4, default 200).
    n_half_layers : int, optional
        N_h, half the number of section layers (≥ 2, default 10).
    plastic : bool, optional
        Layered elastic-plastic section (default); False: linear elastic, exact EI.
    poisson_ratio : float, optional
        ν [-], unused by the beam; for contact laws taking it as target (default 0.3).
    width_constraint : bool, optional
        Wide-section model for b/h > 1 (:mod:`impactmaps.fd.wide_section`, default True).
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
    width_constraint: bool = True

    def __post_init__(self):
        require_positive_fields(self, {"length": "m", "width": "m", "height": "m", "youngs_modulus": "Pa",
                                       "density": "kg/m^3", "yield_strength": "Pa"})
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
        for name, value in _checked_beam_options(self).items():
            object.__setattr__(self, name, value)

    @classmethod
    def from_material(cls, length, width, height, material, **options) -> FDBeam:
        """Build from ``length``, ``width``, ``height`` [m] and a material (``youngs_modulus`` [Pa],
        ``density`` [kg/m³], ``yield_strength`` [Pa], ``poisson_ratio``); ``**options``: other fields."""
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

    @classmethod
    def from_beam(cls, beam, material, settings: FDSettings | None = None) -> FDBeam:
        """The finite-difference model of a rectangular isotropic toolkit ``beam`` of ``material``.

        Geometry and supports come from the beam (``theory`` and ``damping_ratio`` are not
        used); ``settings`` (:class:`FDSettings`) sets grid and section options.

        Raises
        ------
        ValueError
            If ``beam`` is not a rectangular beam of ``material`` (e.g. a laminate).
        """
        if not isinstance(beam, Beam):
            raise ValueError(f"beam = {beam!r} is not an impactmaps.targets.beams.beam.Beam")
        if beam.width is None or beam.height is None:
            raise ValueError("beam.width and beam.height are None: FDBeam.from_beam needs a "
                             "rectangular beam (Beam.rectangular)")
        settings = FDSettings() if settings is None else settings
        made = cls.from_material(beam.length, beam.width, beam.height, material,
                                 supports=SUPPORT_ENDS[beam.supports], **settings.beam_options())
        exact = made.youngs_modulus * made.second_moment
        for name, value, expected in (("bending_stiffness", beam.bending_stiffness, exact),
                                      ("mass_per_length", beam.mass_per_length,
                                       made.mass_per_length)):
            if abs(value - expected) > 1e-9 * expected:
                raise ValueError(
                    f"beam.{name} = {value!r} differs from {expected!r} of a {beam.width:g} m x "
                    f"{beam.height:g} m rectangle of material = {material!r}: FDBeam.from_beam "
                    "needs a rectangular isotropic beam of that material")
        return made

    # -- derived properties ------------------------------------------------------------
    @property
    def section(self) -> LayeredSection:
        """The layered cross-section."""
        saturation, rate = constraint_parameters(self.width, self.height, self.youngs_modulus,
                                                 self.yield_strength) \
            if self.width_constraint else (0.0, 0.0)
        return LayeredSection(self.width, self.height, self.youngs_modulus, self.yield_strength,
                              self.hardening_modulus, self.n_half_layers, saturation, rate)

    @property
    def bending_stiffness(self) -> float:
        """Elastic EI of the model [N m²] (layered ``E I (1 − 1/(4N_h²))`` if plastic)."""
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

    def rayleigh_frequency(self, wavenumber):
        """Rayleigh-beam dispersion ω(k) = sqrt(EI k⁴/(ρA + ρI k²)) [rad/s] at wavenumber k [1/m]."""
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
        """Static deflection per unit point load at ``position`` [m/N] (default mid-span), SS ends only."""
        if self.supports != ("ss", "ss"):
            raise ValueError(f"supports = {self.supports!r}: static_point_compliance needs ('ss', 'ss')")
        x0 = 0.5 * self.length if position is None else float(position)
        require_in_range("position", x0, 0.0, self.length, unit="m")
        return x0**2 * (self.length - x0) ** 2 / (
            3.0 * self.youngs_modulus * self.second_moment * self.length
        )

    def stability_limit(self) -> float:
        """Stable central-difference step of the beam alone, ``2/sqrt(λ*)`` [s] (:func:`grid_frequency_bound`)."""
        return 2.0 / math.sqrt(beam_grid(self).max_eigenvalue)


# =====================================================================================
# Settings of a run
# =====================================================================================
@dataclass(frozen=True)
class FDSettings:
    """Numerical options of a finite-difference impact run (SI units).

    Parameters
    ----------
    n_elements, n_half_layers, plastic, hardening_modulus, damping_per_length, width_constraint : optional
        See :class:`FDBeam`; ``None`` (default) keeps the beam's value.
    gravity : bool, optional
        Standard gravity on the sphere (default False).
    safety_factor : float, optional
        Fraction (0, 1] of the stability limit used by the default step (0.8).
    time_step : float, optional
        Forced Δt [s] (> 0, at most the stability limit).
    history_stride : int, optional
        Record every ``history_stride``-th step (≥ 1, default 1).
    gauge_positions : sequence of float, optional
        Gauge positions [m] (in [0, span]).
    duration : float, optional
        Simulated time [s] (> 0); required by :func:`~impactmaps.fd.simulate_fd`.
    """

    n_elements: int | None = None
    n_half_layers: int | None = None
    plastic: bool | None = None
    hardening_modulus: float | None = None
    damping_per_length: float | None = None
    width_constraint: bool | None = None
    gravity: bool = False
    safety_factor: float = 0.8
    time_step: float | None = None
    history_stride: int = 1
    gauge_positions: tuple = ()
    duration: float | None = None

    def __post_init__(self):
        set_options = {name: getattr(self, name) for name in _BEAM_OPTIONS if getattr(self, name) is not None}
        for name, value in _checked_beam_options(set_options).items():
            object.__setattr__(self, name, value)
        object.__setattr__(self, "gravity", bool(self.gravity))
        require_in_range("safety_factor", self.safety_factor, 0.0, 1.0, low_inclusive=False)
        if self.time_step is not None:
            require_positive("time_step", self.time_step, "s")
        if self.duration is not None:
            require_positive("duration", self.duration, "s")
        object.__setattr__(self, "history_stride", require_stride(self.history_stride))
        positions = tuple(float(x) for x in np.atleast_1d(np.asarray(self.gauge_positions, float)))
        for x in positions:
            require_in_range("gauge_positions", x, 0.0, np.inf, unit="m")
        object.__setattr__(self, "gauge_positions", positions)

    def beam_options(self) -> dict:
        """The FDBeam fields this object sets (those not ``None``)."""
        return {name: getattr(self, name) for name in _BEAM_OPTIONS
                if getattr(self, name) is not None}


def _checked_beam_options(options) -> dict:
    """The grid and section options (an FDBeam or a dict) checked and typed (``ValueError`` otherwise)."""
    values = options if isinstance(options, dict) else {n: getattr(options, n) for n in _BEAM_OPTIONS}
    out = {}
    for name, low in (("n_elements", 4), ("n_half_layers", 2)):
        if name in values:
            value = values[name]
            require_finite(name, value)
            if int(value) != value:
                raise ValueError(f"{name} = {value!r} is invalid: must be an integer >= {low}")
            require_in_range(name, value, low, np.inf)
            out[name] = int(value)
    for name, unit in (("hardening_modulus", "Pa"), ("damping_per_length", "N s/m^2")):
        if name in values:
            require_nonnegative(name, values[name], unit)
    for name in ("plastic", "width_constraint"):
        if name in values:
            out[name] = bool(values[name])
    return out


def require_stride(history_stride) -> int:
    """``history_stride`` as an int ≥ 1 (``ValueError`` naming it otherwise)."""
    require_finite("history_stride", history_stride)
    if int(history_stride) != history_stride:
        raise ValueError(f"history_stride = {history_stride!r} is invalid: must be an integer >= 1")
    require_in_range("history_stride", history_stride, 1, np.inf)
    return int(history_stride)
