r"""Map points with an elastic-plastic contact law: (β, ζ, λ) realised, simulated, scaled.

The ``"yc"``, ``"stronge"`` and ``"epp"`` map families (:class:`PlasticFamily`): ζ and λ
at the linearised stiffness K_y, forces over m V0 ω_y, times × ω_y (docs/plastic_maps.rst).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..._checks import require_choice, require_positive
from ...contact.base import contact_law_class
from ...contact.plastic.epp import EppContact
from ...dimensionless import realise
from ...contact.contact_scale import reference_contact_stiffness
from ...solvers.modal_settings import ModalSettings
from ..family.accuracy import STATUSES, AccuracyControl, PointStatus
from ..family.builtin_families import PLASTIC_ERROR_OF, PLASTIC_LAWS, PlasticLayout, plastic_law_of
from ..family.map_family import RESULT_VARIABLES, PointPlan, register_map_family
from .points import PlanMethod, map_plan, method_code, solve_map_points
from ..family.structures import BasisTable, MapStructure

__all__ = [ "EPP_MAP_OPTIONS", "PLASTIC_VARIABLES", "PlasticNumbers", "PlasticFamily", "plastic_numbers", "realise_plastic",
           "solve_plastic_points"]

#: The options of the ``epp`` law its maps are built at (the law's defaults: the flat's
#: Poisson ratio 0.3, a rigid sphere); each changes the normalised response, so another
#: value is another family.
EPP_MAP_OPTIONS = {name: option.default for name, option in EppContact.options().items()}

#: The variables a plastic map adds to the F̄max ones: name → (units, description).
PLASTIC_VARIABLES = {
    "restitution": ("1", "impactor rebound speed / V0 (nan if the run ended in contact)"),
    "restitution_error": ("1", "error estimate of restitution (as fmax_error)"),
    "absorbed_energy_fraction": ("1", "energy dissipated in the contact / impact energy ½ m V0²"),
    "absorbed_energy_error": ("1", "error estimate of absorbed_energy_fraction (as fmax_error)"),
}
#: The quantities whose error the map stores, with the name of their error variable.
ERROR_OF = PLASTIC_ERROR_OF


@dataclass(frozen=True)
class PlasticNumbers:
    """The similarity numbers and scales of one elastic-plastic impact.

    Attributes
    ----------
    impact_number, loss_factor, relative_stiffness : float
        β = V0/(ω_h α_y), ζ(m, K_y) and λ = K_st/K_y [-].
    linearised_stiffness : float
        K_y = 1.5 K_h sqrt(α_y) [N/m].
    force_scale, time_scale : float
        m V0 ω_y [N] and 1/ω_y [s], ω_y = sqrt(K_y/m).
    """

    impact_number: float
    loss_factor: float
    relative_stiffness: float
    linearised_stiffness: float
    force_scale: float
    time_scale: float


def plastic_numbers(target, law, mass, velocity) -> PlasticNumbers:
    """:class:`PlasticNumbers` of an elastic-plastic impact of ``law`` on ``target`` (a Plate or
    Beam) by an impactor of ``mass`` m > 0 [kg] at ``velocity`` V0 > 0 [m/s].
    """
    plastic_law_of(law)
    require_positive("mass", mass, "kg")
    require_positive("velocity", velocity, "m/s")
    m, v = float(mass), float(velocity)
    hertz, alpha_y = (float(scale) for scale in law.yield_scales)
    stiffness = 1.5 * hertz * math.sqrt(alpha_y)
    omega = math.sqrt(stiffness / m)
    return PlasticNumbers(
        impact_number=v * math.sqrt(1.5) / (omega * alpha_y),
        loss_factor=float(target.loss_factor(m, stiffness)),
        relative_stiffness=float(1.0 / (target.static_compliance() * stiffness)),
        linearised_stiffness=stiffness,
        force_scale=m * v * omega,
        time_scale=1.0 / omega,
    )


def _law_from(map_law: str, hertz: float, alpha_y: float):
    """The contact law of ``map_law`` with Hertz stiffness K_h [N/m^1.5] and yield indentation
    α_y [m], at its default options (an ``epp`` law: :data:`EPP_MAP_OPTIONS`).
    """
    return contact_law_class(PLASTIC_LAWS[map_law]).from_yield_scales(hertz, alpha_y)


@dataclass(frozen=True)
class PlasticRealisation:
    """An impact realising (β, ζ, λ) on a target: law, impactor mass, speed and numbers.

    ``omega`` is the contact frequency [rad/s] of the law's reference stiffness at 1 m/s
    (what a map point's cut-off is a multiple of); ``reflection`` the first wave return
    to the impact point × ω_y [-] (None when not asked for).
    """

    law: object
    mass: float
    velocity: float
    numbers: PlasticNumbers
    omega: float = math.nan
    reflection: float | None = None


def realise_plastic(target, map_law: str, beta: float, zeta: float, lambda_: float,
                    velocity: float = 1.0) -> PlasticRealisation:
    """The elastic-plastic impact (a :class:`PlasticRealisation`) with numbers ``beta``,
    ``zeta``, ``lambda_`` (> 0, at K_y) on ``target`` for ``map_law`` ("yc", "stronge",
    "epp"), at any speed ``velocity`` > 0 [m/s] (the numbers fix the normalised response).
    """
    require_choice("map_law", map_law, tuple(PLASTIC_LAWS))
    require_positive("beta", beta)
    require_positive("velocity", velocity, "m/s")
    impactor = realise(target, zeta, lambda_)
    mass, stiffness = float(impactor.impactor_mass), float(impactor.contact_stiffness)
    alpha_y = math.sqrt(1.5) * float(velocity) / (float(impactor.contact_frequency) * float(beta))
    law = _law_from(map_law, stiffness / (1.5 * math.sqrt(alpha_y)), alpha_y)
    numbers = plastic_numbers(target, law, mass, velocity)
    omega = math.sqrt(reference_contact_stiffness(law, mass, 1.0) / mass)
    return PlasticRealisation(law, mass, float(velocity), numbers, omega,
                              float(target.reflection_time(1.0 / numbers.time_scale)))


class _PlasticScaled:
    """A modal (or asymptote) result read in the plastic scales (what ``controlled_point`` reads)."""

    def __init__(self, result, realised: PlasticRealisation):
        self.result, self.realised = result, realised

    @property
    def fmax_normalised(self) -> float:
        """F_max/(m V0 ω_y) [-]."""
        return self.result.peak_force / self.realised.numbers.force_scale

    @property
    def impacts(self) -> int:
        """Number of separate contacts [-]."""
        return self.result.impacts

    def normalised_summary(self) -> dict:
        """The map scalars: forces over m V0 ω_y, times × ω_y, the energy fractions."""
        return plastic_summary(self.result, self.realised)


def plastic_summary(result, realised: PlasticRealisation) -> dict:
    """The map scalars of a modal run ``result`` of a realised plastic impact: its normalised
    summary with F̄max = F_max/(m V0 ω_y), times × ω_y, ``restitution`` and
    ``absorbed_energy_fraction``.
    """
    summary = result.normalised_summary()
    to_yield_time = 1.0 / (result.contact_frequency * realised.numbers.time_scale)
    for key in ("contact_time_normalised", "first_contact_normalised", "peak_time_normalised"):
        summary[key] = summary[key] * to_yield_time
    impact_energy = 0.5 * realised.mass * realised.velocity**2
    return summary | {
        "fmax_normalised": result.peak_force / realised.numbers.force_scale,
        "restitution": float(result.rebound_velocity / realised.velocity),
        "absorbed_energy_fraction": float(result.contact_dissipation / impact_energy),
    }


def _asymptote_row(plan, realised: PlasticRealisation) -> dict:
    """The map scalars of the any-law infinite-structure answer of a plan."""
    impact, scale = plan.asymptote, realised.numbers.time_scale
    durations = [(end - start) / scale for start, end in impact.contact_intervals]
    separated = np.isfinite(impact.contact_time) and np.isfinite(impact.restitution)
    fmax = impact.peak_force / realised.numbers.force_scale
    absorbed = float(realised.law.dissipated_energy(impact.max_indentation)) / (
        0.5 * realised.mass * realised.velocity**2)
    restitution = float(impact.restitution) if separated else np.nan
    return {
        "fmax_normalised": fmax,
        "impacts": int(impact.impacts),
        "contact_time_normalised": float(sum(durations)) if separated else np.nan,
        "first_contact_normalised": durations[0] if np.isfinite(durations[0]) else np.nan,
        "peak_time_normalised": impact.peak_time / scale,
        "energy_transferred_fraction": 1.0 - restitution**2 - absorbed if separated else np.nan,
        "n_modes": 0,
        "time_limit_reached": int(impact.time_limit_reached),
        "restitution": restitution,
        "absorbed_energy_fraction": absorbed,
        "fmax_error": 0.0, "fmax_low": fmax, "fmax_high": fmax, "status": STATUSES.index(PointStatus.ASYMPTOTIC),
        "restitution_error": 0.0, "absorbed_energy_error": 0.0,
    }


def _companion_errors(runs: list, status: int, levels: int) -> dict:
    """Errors of restitution and absorbed energy from the runs ``controlled_point`` made, as
    its F̄max error (last change between refinement levels, or half the spread).
    """
    out = {}
    for key in ("restitution", "absorbed_energy_fraction"):
        values = np.array([run.normalised_summary()[key] for run in runs])
        if STATUSES[status] == PointStatus.SENSITIVE:
            finest, change = values[levels - 1], abs(values[levels - 1] - values[levels - 2])
            seen = np.concatenate([values, [finest - change, finest + change]])
            error = 0.5 * (np.max(seen) - np.min(seen)) if np.all(np.isfinite(seen)) else np.nan
        else:
            error = abs(values[-1] - values[-2])
        out[ERROR_OF[key]] = float(error)
    return out


#: The descriptions a plastic map gives the variables it shares with the others.
_PLASTIC_DESCRIPTIONS = {"fmax_normalised": "maximum contact force / (m V0 ω_y), ω_y = sqrt(K_y/m)"} | {
    key: RESULT_VARIABLES[key][3].replace("× ω", "× ω_y").replace("ω d²", "ω_y d²")
    for key in ("contact_time_normalised", "first_contact_normalised", "peak_time_normalised",
                "reflection_time_normalised")}


class PlasticFamily(PlasticLayout):
    """An elastic-plastic law's maps over (β, ζ, λ) at K_y: ``name`` the map law (a key of
    :data:`PLASTIC_LAWS`), ``law_options`` the law options its maps are built at (the ``epp``
    family's: :data:`EPP_MAP_OPTIONS`).
    """

    variables = {name: spec[:3] + (_PLASTIC_DESCRIPTIONS.get(name, spec[3]),) for name, spec in RESULT_VARIABLES.items()
                 } | {name: ("f8", np.nan, units, text) for name, (units, text) in PLASTIC_VARIABLES.items()}

    @property
    def method_text(self) -> str:
        return (f"modal impact solver (exact-step integrator, residual flexibility), {PLASTIC_LAWS[self.name]} "
                f"contact{self.law_options_text}; axes (β, λ, ζ) at the linearised stiffness K_y")

    def __init__(self, name: str, law_options: dict | None = None):
        super().__init__(name)
        self._law_options = dict(law_options or {})

    def __reduce__(self):
        return (type(self), (self.name, self._law_options))

    @property
    def law_options(self) -> dict:
        """The contact-law options the maps are built at (name → value; registered with the family)."""
        return dict(self._law_options)

    @property
    def law_options_text(self) -> str:
        """`` (name = value, …)`` of :attr:`law_options`, or ``""``."""
        options = self.law_options
        return " (" + ", ".join(f"{name} = {value:g}" for name, value in options.items()) + ")" if options else ""

    @property
    def law_revision(self) -> int:
        return contact_law_class(PLASTIC_LAWS[self.name]).revision

    def realise(self, target, point) -> PlasticRealisation:
        beta, zeta, lam = (float(value) for value in point)
        return realise_plastic(target, self.name, beta, zeta, lam)

    def plan(self, target, realised: PlasticRealisation, point, cap: float, settings) -> PointPlan:
        plan = map_plan(target, realised.law, realised.mass, realised.omega, settings.cutoff_ratio * realised.omega,
                        cap, None)
        if plan is None:  # beyond the shear-deformable theory, or no method within the mode cap
            return PointPlan(None)
        if plan.method == PlanMethod.ASYMPTOTE:
            return PointPlan(plan.method, _asymptote_row(plan, realised) | {"method": method_code(plan.method)})
        return PointPlan(plan.method)

    def scaled(self, result, realised: PlasticRealisation) -> _PlasticScaled:
        return _PlasticScaled(result, realised)

    def companion_errors(self, runs: list, status: int, levels: int) -> dict:
        return _companion_errors(runs, status, levels)

    def unresolved_extras(self) -> dict:
        return {name: np.nan for name in PLASTIC_VARIABLES}


YC = register_map_family(PlasticFamily("yc"))
STRONGE = register_map_family(PlasticFamily("stronge"))
EPP = register_map_family(PlasticFamily("epp", law_options=EPP_MAP_OPTIONS))


def solve_plastic_points(structure: MapStructure, map_law: str, points: Sequence[tuple[float, float, float]],
                         settings: ModalSettings | None = None, table: BasisTable | None = None,
                         control: AccuracyControl = AccuracyControl()) -> list[dict]:
    """Simulate the elastic-plastic impacts realising each (β, ζ, λ) of ``points`` on
    ``structure`` (:func:`impactmaps.maps.compute.points.solve_map_points` of the family
    ``map_law``).

    Returns
    -------
    list of dict
        One dict per point: the map scalars, their errors, ``status``, ``method``,
        ``reflection_time_normalised`` and ``beta``, ``zeta``, ``lambda_`` (an unresolved
        point's values missing).
    """
    require_choice("map_law", map_law, tuple(PLASTIC_LAWS))
    family = {"yc": YC, "stronge": STRONGE, "epp": EPP}[map_law]
    return solve_map_points(family, structure, points, settings, table, control)
