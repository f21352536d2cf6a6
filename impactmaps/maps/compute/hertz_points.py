"""Map points with the Hertz law: (ζ_h, λ_h) realised, simulated and scaled by the Hertz half-space.

A point is the impact realising (ζ_h, λ_h) on the structure's reference target at 1 m/s,
solved under the linear maps' accuracy control and stored over ``F_hs = K_h α_m^{3/2}``
(forces) and ``t* = α_m/V0`` (times); by Hertz similarity it holds for every case with the
same numbers (:mod:`impactmaps.closed_forms.hertz_similarity`). :class:`HertzFamily` is the
``"hertz"`` map family.
"""

from __future__ import annotations

import functools
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np

from ... import _files
from ...contact.hertz import HertzContact
from ...closed_forms.hertz_similarity import radius_for_patch_number, realise_hertz, unit_speed_stiffness
from ...contact.contact_scale import reference_contact_stiffness
from ...solvers.mode_budget import ASYMPTOTE_REFLECTION_FACTOR
from ...solvers.modal_settings import ModalSettings, uses_patch
from ...targets.shear_range import beyond_shear_theory, has_classical_asymptote
from ...targets.options import default_theory
from ..family.accuracy import AccuracyControl, exact_point
from ..family.builtin_families import HertzLayout
from ..family.map_family import RESULT_VARIABLES, PointPlan, register_map_family
from .points import SOLVER_REVISION, PlanMethod, capped_resolvable, method_code, solve_map_points
from ..family.structures import BasisTable, MapStructure

__all__ = [ "HERTZ_DESCRIPTIONS", "HERTZ_TIME_KEYS", "HertzFamily", "HERTZ", "hertz_asymptote_peak",
           "hertz_contact_frequency", "hertz_summary", "solve_hertz_points"]

#: The map variables that are times (scaled by t* in a Hertz map, by 1/ω in a linear one).
HERTZ_TIME_KEYS = ("contact_time_normalised", "first_contact_normalised", "peak_time_normalised")

#: What the scaled variables of a Hertz map mean (the ``long_name`` of its variables).
HERTZ_DESCRIPTIONS = {
    "fmax_normalised": "maximum contact force / F_hs over all impacts (F_hs = K_h α_m^1.5, the Hertz half-space peak)",
    "contact_time_normalised": "total contact time / t* (t* = α_m/V0)",
    "first_contact_normalised": "duration of the first contact / t*",
    "peak_time_normalised": "time of the maximum force / t*",
    "reflection_time_normalised": "d²/(c t*): first wave return to the impact point (d: distance to nearest "
                                  "support/edge, c = sqrt(bending stiffness / mass per length or area))",
}

#: The structure (of the classical theory) whose target stands for each kind in the Hertz asymptotes (the infinite
#: plate needs ρh and D*, the infinite beam m' and EI; the loss factor is defined on them).
_ASYMPTOTE_STRUCTURES = {
    "plate": MapStructure(kind="plate", theory=default_theory("plate"), supports="SSSS"),
    "beam": MapStructure(kind="beam", theory=default_theory("beam"), supports="ss", impact_fraction=(0.5,)),
}
_INFINITE = {"plate": "infinite-plate", "beam": "infinite-beam"}


class _Realised:
    """The impact realising (ζ_h, λ_h) on a target at 1 m/s: law (with the effective radius of
    a patch number P), mass, speed, scales.
    """

    def __init__(self, target, zeta_h: float, lambda_h: float, patch: float | None = None):
        stiffness = unit_speed_stiffness(target, zeta_h, lambda_h)
        realisation = realise_hertz(target, zeta_h, lambda_h, stiffness)
        radius = None if patch is None else radius_for_patch_number(target, realisation.numbers, patch)
        self.law = HertzContact(stiffness, effective_radius=radius)
        self.mass, self.velocity, self.numbers = realisation.mass, realisation.velocity, realisation.numbers
        self.omega = float(np.sqrt(reference_contact_stiffness(self.law, self.mass, self.velocity) / self.mass))

    def reflection_on(self, target) -> float:
        """The first wave return to the impact point of ``target`` over t* [-]."""
        return float(target.reflection_time(1.0 / self.numbers.time_scale))


class _HertzScaled:
    """A modal :class:`~impactmaps.result.ImpactResult` read in the Hertz scales."""

    def __init__(self, result, numbers):
        self.result, self.numbers = result, numbers

    @property
    def fmax_normalised(self) -> float:
        """F_max / F_hs [-]."""
        return self.result.peak_force / self.numbers.force_scale

    @property
    def impacts(self) -> int:
        """Number of separate contacts [-]."""
        return self.result.impacts

    def normalised_summary(self) -> dict:
        """The map scalars of the run, forces over F_hs and times over t*."""
        return hertz_summary(self.result, self.numbers)


def hertz_contact_frequency(target, zeta_h: float, lambda_h: float) -> float:
    """Contact frequency ω [rad/s] of the impact realising (ζ_h, λ_h) on ``target`` at 1 m/s
    (the frequency the cut-off of its map point is a multiple of)."""
    return _Realised(target, float(zeta_h), float(lambda_h)).omega


def hertz_summary(result, numbers) -> dict:
    """The map scalars of a modal Hertz run ``result`` in the Hertz scales of ``numbers``
    (:class:`~impactmaps.closed_forms.hertz_similarity.HertzNumbers`): F̄max = F_max/F_hs and
    the times (:data:`HERTZ_TIME_KEYS`) in units of t*.
    """
    summary = result.normalised_summary()
    to_hertz_time = 1.0 / (result.contact_frequency * numbers.time_scale)
    for key in HERTZ_TIME_KEYS:
        summary[key] = summary[key] * to_hertz_time
    summary["fmax_normalised"] = result.peak_force / numbers.force_scale
    return summary


def asymptote(which: str, target, law, mass: float, velocity: float):
    """:func:`impactmaps.closed_forms.law_asymptotes.asymptote`, imported on first use (it imports scipy's
    integrators, which a map lookup never runs)."""
    from ...closed_forms.law_asymptotes import asymptote as any_law_asymptote

    return any_law_asymptote(which, target, law, mass, velocity)


def _asymptote_row(which: str, target, zeta_h: float, lambda_h: float) -> dict:
    """The map scalars of an any-law asymptote of the realised Hertz impact."""
    realised = _Realised(target, zeta_h, lambda_h)
    impact = asymptote(which, target, realised.law, realised.mass, realised.velocity)
    scale = realised.numbers.time_scale
    durations = [(end - start) / scale for start, end in impact.contact_intervals]
    contact = float(sum(durations)) if np.isfinite(impact.contact_time) else np.nan  # total, as the modal runs
    return {
        "fmax_normalised": impact.peak_force / realised.numbers.force_scale,
        "impacts": int(impact.impacts),
        "contact_time_normalised": contact,
        "first_contact_normalised": durations[0] if np.isfinite(durations[0]) else np.nan,
        "peak_time_normalised": impact.peak_time / scale,
        "energy_transferred_fraction": 1.0 - impact.restitution**2 if np.isfinite(contact) else np.nan,
        "n_modes": 0,
        "time_limit_reached": int(impact.time_limit_reached),
    }


@functools.lru_cache(maxsize=4096)
def _asymptote_peak(which: str, kind: str, zeta_h: float, lambda_h: float) -> float:
    target = _ASYMPTOTE_STRUCTURES[kind].build()
    return float(_asymptote_row(which, target, zeta_h, lambda_h)["fmax_normalised"])


#: The Hertz asymptote peaks computed before, in a file of the cache directory (beside the
#: on-demand tiles; :func:`impactmaps._files.cache_directory`) named by the solver revision and
#: the Hertz law's (:func:`stored_peaks_path`):
#: a lookup of a case whose tile is cached reads the peaks of its regime instead of integrating
#: them again in every process (~0.1 s). The floats are stored exactly (the same bits); at most
#: :data:`STORED_PEAKS_MAX`, the newest, are kept.
STORED_PEAKS_FILE = "hertz-asymptote-peaks-r{revision}.json"
STORED_PEAKS_MAX = 4096


def stored_peaks_path() -> Path:
    """The file of the stored Hertz asymptote peaks (:data:`STORED_PEAKS_FILE`)."""
    revision = f"{SOLVER_REVISION}.{HertzContact.revision}"
    return _files.cache_directory() / STORED_PEAKS_FILE.format(revision=revision)


def hertz_asymptote_peak(which: str, kind: str, zeta_h=1.0, lambda_h=1.0):
    """F_max/F_hs [-] of a Hertz asymptote (vectorised, cached in memory and on disk,
    :data:`STORED_PEAKS_FILE`): ``which`` "infinite" (plate or beam by ``kind``, a function of
    ``zeta_h``) or "quasi-static" (of ``lambda_h``: ``F̄^{5/3} + (25/16) F̄²/λ_h = 1``); Hertz
    numbers > 0.
    """
    if which not in ("infinite", "quasi-static"):
        raise ValueError(f"which = {which!r} is invalid: choose 'infinite' or 'quasi-static'")
    if kind not in _ASYMPTOTE_STRUCTURES:
        raise ValueError(f"kind = {kind!r} is invalid: choose 'beam' or 'plate'")
    zeta, lam = np.broadcast_arrays(np.asarray(zeta_h, float), np.asarray(lambda_h, float))
    if np.any(~(zeta > 0)) or np.any(~(lam > 0)):
        raise ValueError(f"zeta_h = {zeta_h!r}, lambda_h = {lambda_h!r} are invalid: valid range is (0, inf)")
    name = _INFINITE[kind] if which == "infinite" else "quasi-static"
    # the asymptote depends on one number: pin the other, so the cache sees few keys
    keys = np.stack([zeta, np.ones_like(zeta)] if which == "infinite" else [np.ones_like(lam), lam], axis=-1)
    unique, inverse = np.unique(keys.reshape(-1, 2), axis=0, return_inverse=True)
    numbers = {f"{name} {kind} {float(z)!r} {float(l)!r}": (float(z), float(l)) for z, l in unique}
    peaks = np.array(_files.stored_floats(stored_peaks_path(), list(numbers),
                                          lambda key: _asymptote_peak(name, kind, *numbers[key]), STORED_PEAKS_MAX))
    out = peaks[np.ravel(inverse)].reshape(zeta.shape)
    return float(out) if out.ndim == 0 else out


class HertzFamily(HertzLayout):
    """The Hertz law's maps over the Hertz numbers (ζ_h, λ_h).

    Parameters
    ----------
    patch : float, optional
        Patch number P = sqrt(R α_m)/h [-] of patch-loaded points (:func:`with_patch`);
        None (the registered family): point-loaded.
    """

    variables = {name: spec[:3] + (HERTZ_DESCRIPTIONS.get(name, spec[3]),) for name, spec in RESULT_VARIABLES.items()}

    capped_points = True

    def __init__(self, patch: float | None = None):
        self.patch = patch

    def with_patch(self, patch: float | None) -> "HertzFamily":
        """The Hertz map family of points loaded over the Hertz patch of patch number ``patch`` (None: point load)."""
        return HertzFamily(patch)

    def check(self, structure, target, settings) -> None:
        if self.patch is not None and not uses_patch(target, settings.contact_patch):
            raise ValueError(f"patch = {self.patch!r}: the {structure.name} target takes no contact patch under "
                             f"contact_patch = {settings.contact_patch!r} (valid: patch = None)")

    def uses_table(self) -> bool:
        return self.patch is None

    def realise(self, target, point) -> _Realised:
        zeta, lam = point
        realised = _Realised(target, float(zeta), float(lam), self.patch)
        realised.reflection = realised.reflection_on(target)
        return realised

    def plan(self, target, realised: _Realised, point, cap: float, settings) -> PointPlan:
        zeta, lam = float(point[0]), float(point[1])
        if beyond_shear_theory(target, realised.omega):
            return PointPlan(None)
        ratio = settings.cutoff_ratio if self.patch is None else settings.patch_cutoff_ratio
        capped = ratio * realised.omega > cap
        if capped and self.patch is None and has_classical_asymptote(target):
            infinite = _asymptote_row(_INFINITE[target.kind], target, zeta, lam)
            ends = infinite["contact_time_normalised"]  # exact for the whole event only (NaN: never ends)
            if (realised.reflection >= ASYMPTOTE_REFLECTION_FACTOR * infinite["peak_time_normalised"]
                    and realised.reflection >= ends):
                return PointPlan(PlanMethod.ASYMPTOTE,
                                 exact_point(infinite | {"method": method_code(PlanMethod.ASYMPTOTE)}))
        if capped:  # answered as simulate answers it (halving the cap checks it), or not vouched for
            return PointPlan(PlanMethod.CAPPED if capped_resolvable(target, realised.omega, cap) else None)
        return PointPlan(PlanMethod.MODAL)

    def scaled(self, result, realised: _Realised) -> _HertzScaled:
        return _HertzScaled(result, realised.numbers)

    def runner(self, target, table, cap: float, point, realised, runs: list):
        if self.patch is None:
            return None  # the table runner
        return _patch_runner(self, target, cap, point, realised)

    def infinite_peak(self, loss_factor, kind: str):
        return hertz_asymptote_peak("infinite", kind, zeta_h=loss_factor)

    def quasi_static_peak(self, relative_stiffness):
        return hertz_asymptote_peak("quasi-static", "plate", lambda_h=relative_stiffness)


HERTZ = register_map_family(HertzFamily())


def solve_hertz_points(structure: MapStructure, points: Sequence[tuple[float, float]], settings: ModalSettings,
                       table: BasisTable | None = None, control: AccuracyControl = AccuracyControl(),
                       patch: float | None = None) -> list[dict]:
    """Simulate the Hertz impacts realising each (ζ_h, λ_h) on ``structure``
    (:func:`impactmaps.maps.compute.points.solve_map_points` of the Hertz family; with
    ``patch`` = P, loaded over the Hertz patch, without asymptote): one dict per point, the
    map variables in Hertz scales plus ``zeta``, ``lambda_``.
    """
    return solve_map_points(HERTZ.with_patch(patch), structure, points, settings, table, control)


def _patch_runner(family: HertzFamily, target, cap: float, point, realised: _Realised):
    """``run(settings, zeta_factor)`` of one patch-loaded Hertz point, read in the Hertz scales,
    its cut-off clipped to ``cap`` [rad/s]. A plate of the general Ritz basis runs on the one
    basis resolving ``cap`` (:func:`~impactmaps.targets.plates.shared_basis.shared_basis`):
    the points of a tile or a sweep share it instead of building one per cut-off.
    """
    from ...solvers.modal import simulate  # the integrator: only where a point is computed
    from ...targets.plates.shared_basis import shared_basis

    target = shared_basis(target, cap)  # a general-basis plate: one basis (at the cap) for every run and point

    def run(settings: ModalSettings, zeta_factor: float):
        impact = realised if zeta_factor == 1.0 else family.realise(target, family.moved(point, zeta_factor))
        clipped = replace(settings, patch_cutoff_ratio=min(settings.patch_cutoff_ratio, cap / impact.omega))
        result = simulate(target, impact.law, impact.mass, impact.velocity, settings=clipped, record=False,
                          corner_cutoff=False)  # the point's accuracy control refines its cut-off
        return _HertzScaled(result, impact.numbers)

    return run
