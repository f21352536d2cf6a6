"""Layered elastic-plastic rectangular cross-section (seed 000; spec section 5).

The section of width ``b`` and height ``h`` is cut into ``2 N_h`` layers of equal
thickness ``Δz = h / (2 N_h)``; each layer carries one uniaxial stress evaluated at its
mid-plane ``z_i = −h/2 + (i + ½) Δz`` (midpoint rule through the thickness).

Sign conventions (used throughout :mod:`impactmaps.fd`)
-------------------------------------------------------
``w`` (deflection) and ``z`` both point in the impact direction ("down"); the impacted
face is ``z = −h/2``. The axial strain is ``ε = −z κ`` with curvature ``κ = w''``, so a
sagging beam (``κ < 0`` under a downward load) stretches the far face ``z = +h/2``.
The bending moment is the sagging moment ``M = b Σ σ_i z_i Δz``; in the elastic range
``M = −E I_h κ`` with the layered second moment ``I_h = b Σ z_i² Δz``.

Midpoint rule and its error
---------------------------
``I_h = (b h³/12)(1 − 1/(4 N_h²))`` exactly (each layer misses ``b Δz³/12``), so the
elastic stiffness is second order in ``1/N_h``; the fully plastic moment
``b σ_y Σ |z_i| Δz = σ_y b h²/4`` is exact for every ``N_h`` (``|z|`` is linear in each
layer). In the elastic-plastic range the error of ``M(κ)`` is ``O(N_h⁻²)`` but not
monotonic (the elastic-plastic interface moves across layers).

Material model
--------------
Each layer is elastic–perfectly plastic (yield stress ``σ_y``) or, with
``hardening_modulus = H > 0``, elastic–linear **kinematic** (Prager) hardening:
yield function ``|σ − β| ≤ σ_y`` with back stress ``β``, ``dβ = H dε_p``, so ``H`` is the
*plastic* modulus (slope of stress against plastic strain) and the tangent modulus in
monotonic loading is ``E_t = E H / (E + H)``. Kinematic hardening is chosen because beam
impact unloads and reverses the stress in the plastic zone (rebound, vibration), where it
gives the Bauschinger effect and a constant elastic range ``2 σ_y``; in monotonic loading
it coincides with isotropic hardening. The return mapping in 1-D is exact for a strain
increment of any size (closed form), so the stress update introduces no time-step error.

A wide section (b/h > 1, :mod:`impactmaps.fd.wide_section`) adds a saturating
(Armstrong–Frederick) kinematic back stress β_c ≤ β_sat for the plastic hinge held across
the width; its return needs a scalar Newton solve (convex, monotone convergence), exact
to round-off for an increment of any size. Without it (β_sat = 0) the section is the
uniaxial one above.

Energy: per unit volume the strain energy is ``σ²/(2E)`` and the plastic work increment
is ``W_p += ½(σ_old + σ_new) Δε_p`` (trapezoidal rule). With that choice
``½(σ_old + σ_new) Δε = Δ(σ²/(2E)) + ΔW_p`` holds *exactly* for every increment, so the
internal work splits into elastic energy and plastic work without discretisation error.
The trapezoid is exact for an increment that is plastic throughout (σ is linear in ε_p);
for one that starts elastic its error is ``½(σ_old − σ_Y) Δε_p`` (σ_Y: stress where
yielding starts), second order in the increment. With hardening, ``W_p`` includes the
energy ``β²/(2H)`` locked in the back stress (the part truly dissipated is
``W_p − β²/(2H)``), and a reverse flow at a stress of the "wrong" sign (``|β| > σ_y``)
legitimately gives ``ΔW_p < 0``; without hardening ``ΔW_p ≥ 0`` always.
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
    "SectionState",
    "stress_update",
    "rectangular_moment_curvature",
]


# -- the one implementation of the layer stress update --------------------------------
@numba.njit(cache=True)
def return_map(stress, back_stress, constraint_stress, strain_increment, youngs_modulus,
               yield_strength, hardening_modulus, constraint_saturation, constraint_rate):
    """Elastic predictor / return mapping for one layer (scalar numba kernel).

    The back stress is ``β = β_H + β_c``: the linear kinematic part ``dβ_H = H dε_p`` and
    the width-constraint part (Armstrong–Frederick form) ``dβ_c = γ (β_sat sign(dε_p) −
    β_c) |dε_p|``, which saturates at ``±β_sat`` (:mod:`impactmaps.fd.wide_section`;
    ``β_sat = 0``: no constraint, the closed-form linear return). With the constraint the
    plastic multiplier solves ``excess = (E + H) Δλ + a (1 − e^{−γ Δλ})`` (``a = β_sat −
    n β_c ≥ 0``), convex and decreasing in Δλ: Newton from Δλ = 0 converges monotonically;
    the β_c update is exact for the increment.

    Parameters
    ----------
    stress, back_stress, constraint_stress : float
        Stress σ*, total back stress β and its constraint part β_c at the previous step [Pa].
    strain_increment : float
        Total strain increment Δε [-].
    youngs_modulus, yield_strength, hardening_modulus : float
        E, σ_y and plastic (kinematic) hardening modulus H [Pa].
    constraint_saturation : float
        β_sat [Pa] (0: none).
    constraint_rate : float
        γ [-] (1/plastic strain).

    Returns
    -------
    stress, back_stress, constraint_stress, plastic_strain_increment, plastic_work_density : float
        Updated σ, β and β_c [Pa], Δε_p [-], and ΔW_p = ½(σ* + σ) Δε_p [J/m³].
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

    Parameters
    ----------
    stress, back_stress, strain_increment : array_like
        Previous stress σ* [Pa], total back stress β [Pa] and strain increment Δε [-];
        broadcast together (e.g. shape ``(n_nodes, n_layers)``).
    youngs_modulus, yield_strength : float
        E [Pa] and initial yield stress σ_y [Pa].
    hardening_modulus : float, optional
        Linear kinematic plastic modulus H [Pa] (0: perfectly plastic).
    constraint_stress : array_like, optional
        Previous width-constraint part β_c of the back stress [Pa] (broadcast as above).
    constraint_saturation, constraint_rate : float, optional
        β_sat [Pa] and γ [-] of the width constraint (:func:`return_map`; 0: none).

    Returns
    -------
    stress, back_stress, plastic_strain_increment, plastic_work_density : ndarray
        New σ [Pa], β [Pa], Δε_p [-] and plastic work per unit volume ΔW_p [J/m³]; with
        ``constraint_saturation > 0`` the new β_c [Pa] follows as a fifth array.
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
        Curvature κ = w'' at the last update [1/m].
    stress, back_stress, plastic_strain : ndarray, shape (n_points, 2 N_h)
        Layer stress σ [Pa], back stress β [Pa] and accumulated plastic strain ε_p [-].
    constraint_stress : ndarray, shape (n_points, 2 N_h)
        The width-constraint part β_c of the back stress [Pa] (0 without it).
    plastic_work : ndarray, shape (n_points,)
        Accumulated plastic work per unit length of beam [J/m].
    """

    curvature: np.ndarray
    stress: np.ndarray
    back_stress: np.ndarray
    plastic_strain: np.ndarray
    plastic_work: np.ndarray
    constraint_stress: np.ndarray


@dataclass(frozen=True)
class LayeredSection:
    """Rectangular cross-section made of ``2 N_h`` elastic-plastic layers.

    Parameters
    ----------
    width : float
        Section width b [m].
    height : float
        Section height h [m] (in the impact direction).
    youngs_modulus : float
        Young's modulus E [Pa].
    yield_strength : float
        Uniaxial yield stress σ_y [Pa].
    hardening_modulus : float, optional
        Linear kinematic plastic modulus H [Pa]; 0 (default) is perfectly plastic.
    n_half_layers : int, optional
        N_h; the section has ``2 N_h`` layers (≥ 2, default 10).
    constraint_saturation : float, optional
        β_sat [Pa]: the width-constraint back stress saturates at ±β_sat, so the fully
        plastic moment tends to ``(σ_y + β_sat) b h²/4``; 0 (default): the uniaxial
        section (:mod:`impactmaps.fd.wide_section` gives it for a wide beam).
    constraint_rate : float, optional
        γ [-]: the constraint back stress reaches 1 − 1/e of β_sat after a plastic strain
        1/γ (needed > 0 when ``constraint_saturation > 0``).
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
    def area(self) -> float:
        """A = b h [m²]."""
        return self.width * self.height

    @property
    def second_moment(self) -> float:
        """Exact I = b h³ / 12 [m⁴]."""
        return self.width * self.height**3 / 12.0

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
        """Moment the section tends to at large curvature, ``(σ_y + β_sat) b h² / 4``
        (= :attr:`plastic_moment` without the width constraint; perfectly plastic
        layers) [N m]."""
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
        """Advance ``state`` (in place) to the new curvatures and return the moments.

        Parameters
        ----------
        state : SectionState
            Layer state; updated in place (stress, back stress, plastic strain,
            plastic work, curvature).
        curvature : array_like, shape (n_points,)
            New curvature κ = w'' [1/m].

        Returns
        -------
        ndarray, shape (n_points,)
            Sagging moments M [N m].
        """
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
        """Moments [N m] along a curvature path starting from the virgin state.

        The path is followed increment by increment with :func:`stress_update` (the
        same update as the beam solver); for a monotonic path this is the monotonic
        moment–curvature curve. ``curvatures`` are w'' values [1/m]; for the usual
        positive (sagging) moment–curvature plot pass ``-κ``.

        Parameters
        ----------
        curvatures : array_like, shape (n,)
            Curvature path κ_1, κ_2, … [1/m].

        Returns
        -------
        ndarray, shape (n,)
            Sagging moment at each point of the path [N m].
        """
        path = np.atleast_1d(np.asarray(curvatures, dtype=float))
        state = self.initial_state(1)
        moments = np.empty(path.size)
        for i, kappa in enumerate(path):
            moments[i] = self.update(state, [kappa])[0]
        return moments


def rectangular_moment_curvature(curvature, width, height, youngs_modulus, yield_strength):
    """Exact monotonic moment–curvature of an elastic–perfectly plastic rectangle.

    ``M = E I κ`` for ``κ ≤ κ_y`` and ``M = M_p (1 − (κ_y/κ)²/3)`` above, with
    ``κ_y = 2σ_y/(E h)``, ``M_p = σ_y b h²/4 = 1.5 M_y`` (e.g. Lubliner, *Plasticity
    Theory*, 2008, §4.4; any strength-of-materials text).

    Parameters
    ----------
    curvature : array_like
        Curvature magnitude |κ| [1/m].
    width, height : float
        b, h [m].
    youngs_modulus, yield_strength : float
        E, σ_y [Pa].

    Returns
    -------
    ndarray
        Moment magnitude [N m].
    """
    kappa = np.abs(np.asarray(curvature, dtype=float))
    kappa_y = 2.0 * yield_strength / (youngs_modulus * height)
    plastic_moment = yield_strength * width * height**2 / 4.0
    elastic = youngs_modulus * width * height**3 / 12.0 * kappa
    with np.errstate(divide="ignore"):
        plastic = plastic_moment * (1.0 - (kappa_y / np.where(kappa > 0, kappa, 1.0)) ** 2 / 3.0)
    return np.where(kappa <= kappa_y, elastic, plastic)
