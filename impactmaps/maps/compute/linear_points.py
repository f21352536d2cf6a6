"""The linear map family: (ζ, λ) of docs/physics_contract.md §4, F̄max = F_max/(m V0 ω), times × ω.

A point is the impactor of :func:`impactmaps.dimensionless.realise` on the structure's
reference target (a linear spring K at 1 m/s); past the mode cap the infinite-structure
solution answers where exact for the peak. Regime asymptotes: eqs 28, 32, 36.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np

from ...closed_forms.asymptotes import quasi_static_peak
from ...contact.linear import LinearContact
from ...dimensionless import realise
from ...solvers.modal_settings import ModalSettings
from ...targets import target_class
from ..family.accuracy import AccuracyControl, exact_point
from ..family.builtin_families import LinearLayout
from ..family.map_family import PointPlan, register_map_family
from .points import PlanMethod, map_plan, method_code, solve_map_points
from ..family.structures import BasisTable, MapStructure

__all__ = ["LinearFamily", "LINEAR", "solve_points"]


class LinearImpact(NamedTuple):
    """A linear-contact impact realising (ζ, λ) at 1 m/s [SI]; ``reflection`` = ω d²/c [-]."""

    law: LinearContact
    mass: float
    velocity: float
    omega: float
    reflection: float
    stiffness: float


class LinearFamily(LinearLayout):
    """The linear contact law's maps (module docstring); its layout (axes, shipped maps):
    :class:`~impactmaps.maps.family.builtin_families.LinearLayout`."""

    capped_points = True

    def realise_points(self, target, points) -> list:
        zetas = np.array([p[0] for p in points], dtype=float)
        lambdas = np.array([p[1] for p in points], dtype=float)
        impactors = realise(target, zetas, lambdas)
        omegas = np.atleast_1d(impactors.contact_frequency)
        masses = np.atleast_1d(impactors.impactor_mass)
        stiffnesses = np.atleast_1d(impactors.contact_stiffness)
        reflections = np.atleast_1d(target.reflection_time(omegas))
        return [LinearImpact(LinearContact(float(k)), float(m), 1.0, float(w), float(r), float(k))
                for m, k, w, r in zip(masses, stiffnesses, omegas, reflections)]

    def realise(self, target, point) -> LinearImpact:
        zeta, lam = point
        moved = realise(target, zeta, lam)
        omega, stiffness = float(moved.contact_frequency), float(moved.contact_stiffness)
        return LinearImpact(LinearContact(stiffness), float(moved.impactor_mass), 1.0, omega,
                            float(target.reflection_time(omega)), stiffness)

    def plan(self, target, realised: LinearImpact, point, cap: float, settings) -> PointPlan:
        zeta = float(point[0])
        plan = map_plan(target, realised.law, realised.mass, realised.omega, settings.cutoff_ratio * realised.omega,
                        cap, zeta, capped=True)
        if plan is None:
            return PointPlan(None)
        if plan.method == PlanMethod.ASYMPTOTE:
            return PointPlan(plan.method, exact_point(infinite_structure_row(target, zeta)))
        return PointPlan(plan.method)

    def infinite_peak(self, loss_factor, kind: str):
        return target_class(kind).infinite_structure_peak(loss_factor)

    def quasi_static_peak(self, relative_stiffness):
        return quasi_static_peak(relative_stiffness)


def infinite_structure_row(target, zeta: float) -> dict:
    """Map scalars of the infinite-structure solution at ζ (exact until waves return)."""
    impact = target.infinite_structure_impact(zeta)
    contact, rebound = impact.contact_time, impact.rebound_velocity
    contact = float(contact) if np.isfinite(contact) else np.nan
    return {
        "fmax_normalised": float(impact.peak_force),
        "impacts": 1,
        "contact_time_normalised": contact,
        "first_contact_normalised": contact,
        "peak_time_normalised": float(impact.peak_time),
        "energy_transferred_fraction": float(1.0 - float(rebound) ** 2) if np.isfinite(rebound) else np.nan,
        "n_modes": 0,
        "time_limit_reached": 0,
        "method": method_code(PlanMethod.ASYMPTOTE),
    }


LINEAR = register_map_family(LinearFamily())


def solve_points(structure: MapStructure, points: Sequence[tuple[float, float]], settings: ModalSettings,
                 table: BasisTable | None = None, control: AccuracyControl = AccuracyControl()) -> list[dict]:
    """Simulate the linear-contact impacts realising each (ζ, λ) of ``points`` on ``structure``
    (:func:`impactmaps.maps.compute.points.solve_map_points` of the linear family, ``table``
    and ``control`` as there): one dict of normalised scalars per point (keys of
    ``RESULT_VARIABLES`` plus ``zeta``, ``lambda_``).
    """
    return solve_map_points(LINEAR, structure, points, settings, table, control)
