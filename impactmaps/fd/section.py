"""Layered elastic-plastic rectangular cross-section (seed 000; spec section 5).

``2 N_h`` layers of uniaxial stress at their mid-planes; elastic–perfectly plastic or
linear kinematic hardening, with the optional width constraint of
:mod:`impactmaps.fd.wide_section`. Sign conventions and derivations: docs/fd_beam.rst.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from .._checks import (
    require_finite,
    require_in_range,
    require_nonnegative,
    require_positive,
)

__all__ = [
    "LayeredSection",
    "Rectangle",
    "SectionState",
    "stress_update",
    "rectangular_moment_curvature",
]


# -- the one implementation of the layer stress update --------------------------------
@numba.njit(cache=True)
def return_map(stress, back_stress, constraint_stress, strain_increment, youngs_modulus,
               yield_strength, hardening_modulus, constraint_saturation, constraint_rate):
    """Elastic predictor / return mapping for one layer (scalar numba kernel).

    From σ*, β, β_c [Pa] and Δε [-] with E, σ_y, H, β_sat [Pa] and γ [-], returns the new
    ``(σ, β, β_c [Pa], Δε_p [-], ΔW_p = ½(σ* + σ) Δε_p [J/m³])``.
    """
    trial = stress + youngs_modulus * strain_increment
    relative = trial - back_stress
    excess = abs(relative) - yield_strength
    if excess <= 0.0:
        return trial, back_stress, constraint_stress, 0.0, 0.0
    direction = 1.0 if relative > 0.0 else -1.0
    slope = youngs_modulus + hardening_modulus
    new_constraint = constraint_stress
    if constraint_saturation > 0.0:
        span = constraint_saturation - direction * constraint_stress
        multiplier = 0.0
        for _ in range(60):
            decay = math.exp(-constraint_rate * multiplier)
            residual = excess - slope * multiplier - span * (1.0 - decay)
            step = residual / (slope + span * constraint_rate * decay)
            multiplier += step
            if step <= 1e-15 * multiplier:
                break
        new_constraint = direction * constraint_saturation \
            - direction * span * math.exp(-constraint_rate * multiplier)
    else:
        multiplier = excess / slope
    new_stress = trial - youngs_modulus * multiplier * direction
    new_back = back_stress + hardening_modulus * multiplier * direction \
        + (new_constraint - constraint_stress)
    plastic_increment = multiplier * direction
    work = 0.5 * (stress + new_stress) * plastic_increment
    return new_stress, new_back, new_constraint, plastic_increment, work


@numba.njit(cache=True)
def _update_flat(stress, back_stress, constraint_stress, strain_increment, youngs_modulus,
                 yield_strength, hardening_modulus, constraint_saturation, constraint_rate):
    n = stress.shape[0]
    new_stress = np.empty(n)
    new_back = np.empty(n)
    new_constraint = np.empty(n)
    plastic = np.empty(n)
    work = np.empty(n)
    for i in range(n):
        s, b, c, p, w = return_map(stress[i], back_stress[i], constraint_stress[i],
                                   strain_increment[i], youngs_modulus, yield_strength,
                                   hardening_modulus, constraint_saturation, constraint_rate)
        new_stress[i] = s
        new_back[i] = b
        new_constraint[i] = c
        plastic[i] = p
        work[i] = w
    return new_stress, new_back, new_constraint, plastic, work


def stress_update(stress, back_stress, strain_increment, youngs_modulus, yield_strength,
                  hardening_modulus=0.0, constraint_stress=0.0, constraint_saturation=0.0,
                  constraint_rate=0.0):
    """Vectorised layer stress update ``σ = σ* + E Δε`` returned to ``|σ − β| ≤ σ_y``.

    Arguments as :func:`return_map`, arrays broadcast together; ``hardening_modulus``,
    ``constraint_stress``, ``constraint_saturation`` and ``constraint_rate`` default to 0.

    Returns
    -------
    stress, back_stress, plastic_strain_increment, plastic_work_density : ndarray
        σ, β [Pa], Δε_p [-], ΔW_p [J/m³]; with ``constraint_saturation > 0`` the new β_c
        [Pa] follows as a fifth array.
    """
    arrays = np.broadcast_arrays(
        np.asarray(stress, float), np.asarray(back_stress, float),
        np.asarray(constraint_stress, float), np.asarray(strain_increment, float),
    )
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a.ravel()) for a in arrays]
    out = _update_flat(flat[0], flat[1], flat[2], flat[3], float(youngs_modulus),
                       float(yield_strength), float(hardening_modulus),
                       float(constraint_saturation), float(constraint_rate))
    stress, back, constraint, plastic, work = (o.reshape(shape) for o in out)
    if constraint_saturation > 0.0:
        return stress, back, plastic, work, constraint
    return stress, back, plastic, work


# -- the section ----------------------------------------------------------------------
@dataclass
class SectionState:
    """Mutable layer state of a set of sections (one row per beam node).

    Attributes
    ----------
    curvature : ndarray, shape (n_points,)
        κ = w'' [1/m].
    stress, back_stress, plastic_strain : ndarray, shape (n_points, 2 N_h)
        σ [Pa], β [Pa], accumulated ε_p [-].
    constraint_stress : ndarray, shape (n_points, 2 N_h)
        Width-constraint part β_c of the back stress [Pa].
    plastic_work : ndarray, shape (n_points,)
        Plastic work per unit length [J/m].
    """

    curvature: np.ndarray
    stress: np.ndarray
    back_stress: np.ndarray
    plastic_strain: np.ndarray
    plastic_work: np.ndarray
    constraint_stress: np.ndarray


class Rectangle:
    """Area and second moment of a ``width`` × ``height`` rectangle [m] (for the beam and its section)."""

    @property
    def area(self) -> float:
        """A = b h [m²]."""
        return self.width * self.height

    @property
    def second_moment(self) -> float:
        """Exact I = b h³ / 12 [m⁴]."""
        return self.width * self.height**3 / 12.0


@dataclass(frozen=True)
class LayeredSection(Rectangle):
    """Rectangular cross-section made of ``2 N_h`` elastic-plastic layers.

    Parameters
    ----------
    width, height : float
        b and h [m] (h in the impact direction).
    youngs_modulus, yield_strength : float
        E and σ_y [Pa].
    hardening_modulus : float, optional
        Linear kinematic plastic modulus H [Pa]; 0 (default): perfectly plastic.
    n_half_layers : int, optional
        N_h ≥ 2 (default 10).
    constraint_saturation, constraint_rate : float, optional
        β_sat [Pa] and γ [-] of the width constraint (:mod:`impactmaps.fd.wide_section`);
        0 (default): uniaxial section; γ > 0 needed when β_sat > 0.
    """

    width: float
    height: float
    youngs_modulus: float
    yield_strength: float
    hardening_modulus: float = 0.0
    n_half_layers: int = 10
    constraint_saturation: float = 0.0
    constraint_rate: float = 0.0

    def __post_init__(self):
        require_positive("width", self.width, "m")
        require_positive("height", self.height, "m")
        require_positive("youngs_modulus", self.youngs_modulus, "Pa")
        require_positive("yield_strength", self.yield_strength, "Pa")
        require_nonnegative("hardening_modulus", self.hardening_modulus, "Pa")
        require_finite("n_half_layers", self.n_half_layers)
        if int(self.n_half_layers) != self.n_half_layers:
            raise ValueError(
                f"n_half_layers = {self.n_half_layers!r} is invalid: must be an integer >= 2"
            )
        require_in_range("n_half_layers", self.n_half_layers, 2, np.inf)
        object.__setattr__(self, "n_half_layers", int(self.n_half_layers))
        require_nonnegative("constraint_saturation", self.constraint_saturation, "Pa")
        if self.constraint_saturation > 0.0:
            require_positive("constraint_rate", self.constraint_rate, "-")

    # -- geometry ------------------------------------------------------------------
    @property
    def n_layers(self) -> int:
        """Number of layers 2 N_h."""
        return 2 * self.n_half_layers

    @property
    def layer_thickness(self) -> float:
        """Δz = h / (2 N_h) [m]."""
        return self.height / self.n_layers

    @property
    def layer_positions(self) -> np.ndarray:
        """Mid-plane coordinates z_i [m], from the impacted face (−h/2) downwards."""
        dz = self.layer_thickness
        return -0.5 * self.height + (np.arange(self.n_layers) + 0.5) * dz

    @property
    def layered_second_moment(self) -> float:
        """Midpoint-rule I_h = b Σ z_i² Δz = I (1 − 1/(4 N_h²)) [m⁴]."""
        z = self.layer_positions
        return float(self.width * np.sum(z**2) * self.layer_thickness)

    @property
    def yield_moment(self) -> float:
        """First-yield moment M_y = σ_y b h² / 6 [N m] (exact section)."""
        return self.yield_strength * self.width * self.height**2 / 6.0

    @property
    def plastic_moment(self) -> float:
        """Fully plastic moment M_p = σ_y b h² / 4 = 1.5 M_y [N m]."""
        return self.yield_strength * self.width * self.height**2 / 4.0

    @property
    def limit_moment(self) -> float:
        """Moment at large curvature, ``(σ_y + β_sat) b h² / 4`` [N m]."""
        return (self.yield_strength + self.constraint_saturation) * self.width * self.height**2 / 4.0

    @property
    def yield_curvature(self) -> float:
        """Curvature magnitude at first yield κ_y = 2 σ_y / (E h) [1/m]."""
        return 2.0 * self.yield_strength / (self.youngs_modulus * self.height)

    # -- state and update --------------------------------------------------------
    def initial_state(self, n_points: int = 1) -> SectionState:
        """Virgin, stress-free state for ``n_points`` sections."""
        shape = (int(n_points), self.n_layers)
        return SectionState(
            curvature=np.zeros(shape[0]),
            stress=np.zeros(shape),
            back_stress=np.zeros(shape),
            plastic_strain=np.zeros(shape),
            plastic_work=np.zeros(shape[0]),
            constraint_stress=np.zeros(shape),
        )

    def moment(self, stress) -> np.ndarray:
        """Sagging moment M = b Σ σ_i z_i Δz [N m] from layer stresses (..., 2 N_h) [Pa]."""
        stress = np.asarray(stress, dtype=float)
        return self.width * self.layer_thickness * stress @ self.layer_positions

    def update(self, state: SectionState, curvature) -> np.ndarray:
        """Advance ``state`` in place to ``curvature`` κ [1/m]; return sagging moments M [N m]."""
        curvature = np.asarray(curvature, dtype=float)
        z = self.layer_positions
        strain_increment = -np.outer(curvature - state.curvature, z)
        stress, back, constraint, plastic, work = _update_flat(
            *(np.ascontiguousarray(a, dtype=float).ravel() for a in np.broadcast_arrays(
                state.stress, state.back_stress, state.constraint_stress, strain_increment)),
            float(self.youngs_modulus), float(self.yield_strength), float(self.hardening_modulus),
            float(self.constraint_saturation), float(self.constraint_rate))
        stress, back, constraint, plastic, work = (
            a.reshape(state.stress.shape) for a in (stress, back, constraint, plastic, work))
        state.constraint_stress[...] = constraint
        state.stress[...] = stress
        state.back_stress[...] = back
        state.plastic_strain[...] += plastic
        state.plastic_work[...] += self.width * self.layer_thickness * work.sum(axis=-1)
        state.curvature[...] = curvature
        return self.moment(stress)

    def moment_curvature(self, curvatures) -> np.ndarray:
        """Sagging moments [N m] along a path of ``curvatures`` κ [1/m] from the virgin state
        (pass ``-κ`` for the usual positive plot)."""
        path = np.atleast_1d(np.asarray(curvatures, dtype=float))
        state = self.initial_state(1)
        moments = np.empty(path.size)
        for i, kappa in enumerate(path):
            moments[i] = self.update(state, [kappa])[0]
        return moments


def rectangular_moment_curvature(curvature, width, height, youngs_modulus, yield_strength):
    """Exact monotonic moment [N m] of an elastic–perfectly plastic b × h rectangle at |κ| [1/m]."""
    kappa = np.abs(np.asarray(curvature, dtype=float))
    kappa_y = 2.0 * yield_strength / (youngs_modulus * height)
    plastic_moment = yield_strength * width * height**2 / 4.0
    elastic = youngs_modulus * width * height**3 / 12.0 * kappa
    with np.errstate(divide="ignore"):
        plastic = plastic_moment * (1.0 - (kappa_y / np.where(kappa > 0, kappa, 1.0)) ** 2 / 3.0)
    return np.where(kappa <= kappa_y, elastic, plastic)
