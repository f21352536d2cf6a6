"""What a map family is: its axes, its points, its variables, its asymptotes — and the registry.

A *map family* is one contact law's normalised impact map: the numbers that fix an
impact of that law on a structure family (ζ, λ for every law; β too for an
elastic-plastic one), how a point with those numbers is realised as a physical impact
on a :class:`~impactmaps.maps.family.structures.MapStructure`'s reference target and how its
result is scaled back, which variables its map stores, the asymptotes its regimes are
measured against, how its lookups interpolate and which maps the package ships of it.
Each family is one :class:`MapFamily` object registered under its name (the map law:
``"linear"``, ``"hertz"``, ``"yc"``, ``"stronge"``); the sweep
(:func:`impactmaps.maps.compute.sweep.sweep`), the point solver (:mod:`impactmaps.maps.compute.points`),
the map reader (:mod:`impactmaps.maps.read.reader`) and the regimes ask the family, never
its name. Adding a family is one module defining a subclass and one
:func:`register_map_family` call (``docs/map_families.rst``).

This module holds the interface and the registry only; the built-in families live in
:mod:`.linear_points`, :mod:`.hertz_points` and :mod:`.plastic_points` (their layouts, what a
map reader needs, in :mod:`.builtin_families`). The registry knows the built-in names from the
start and imports a built-in family's module when that family is first asked for
(:func:`map_family`): the point solvers it imports are not loaded by a lookup.
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple

import numpy as np

from ..._checks import require_choice

__all__ = ["RESULT_VARIABLES", "ASYMPTOTE_PEAK_VARIABLES", "ASYMPTOTE_PEAKS", "map_law", "Axis", "PointPlan", "Interpolation", "MapFamily", "register_map_family",
           "map_family", "available_map_families"]

#: The variables of every map: name → (dtype, missing value, units, description).
RESULT_VARIABLES = {
    "fmax_normalised": ("f8", np.nan, "1", "maximum contact force / (m_i V0 ω) over all impacts"),
    "impacts": ("i4", -1, "1", "number of separate contacts"),
    "contact_time_normalised": ("f8", np.nan, "1", "total contact time × ω"),
    "first_contact_normalised": ("f8", np.nan, "1", "duration of the first contact × ω"),
    "peak_time_normalised": ("f8", np.nan, "1", "time of the maximum force × ω"),
    "energy_transferred_fraction": ("f8", np.nan, "1", "vibration energy left in the structure / impact energy"),
    "reflection_time_normalised": ("f8", np.nan, "1", "ω d²/c: first wave return to the impact point (d: distance to nearest support/edge, c = sqrt(bending stiffness / mass per length or area))"),
    "n_modes": ("i4", -1, "1", "number of modes integrated"),
    "time_limit_reached": ("i1", -1, "1", "1 if the run stopped at its time limit"),
    "method": ("i1", -1, "1", "which model produced the point: see flag_meanings"),
    "fmax_error": ("f8", np.nan, "1", "error estimate of fmax_normalised (change under refinement, or half the spread of a sensitive point)"),
    "fmax_low": ("f8", np.nan, "1", "lower end of the band that holds fmax_normalised"),
    "fmax_high": ("f8", np.nan, "1", "upper end of the band that holds fmax_normalised"),
    "status": ("i1", -1, "1", "converged, refined, sensitive, asymptotic or unresolved: see flag_meanings"),
}

#: The asymptote peaks a classifying family's (ζ, λ) maps store, the inputs of their regime
#: criteria (:func:`impactmaps.maps.family.regimes.classify`): name → (the one axis it varies along,
#: units, description). Each is stored per structure and grid value of its axis
#: (:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`, :meth:`MapFamily.asymptote_peaks`)
#: and a lookup interpolates it linearly in log peak against the log of that axis.
ASYMPTOTE_PEAK_VARIABLES = {
    "infinite_structure_peak": ("zeta", "1", "normalised peak force of the infinite structure"),
    "quasi_static_peak": ("lambda_", "1", "normalised quasi-static peak force"),
}

#: The variables holding a (ζ, λ) map's asymptote peaks
#: (:func:`impactmaps.maps.compute.dataset.with_asymptote_peaks`).
ASYMPTOTE_PEAKS = tuple(ASYMPTOTE_PEAK_VARIABLES)


def map_law(dataset) -> str:
    """The map law (the name of its map family) a map dataset was swept with (a map without the attribute is linear).

    The law is part of a map's identity: it is in the fingerprint (for every law but the
    linear one, whose fingerprints predate it), in the ``contact_law`` attribute (the stored
    name of the map law, kept for the stored maps) and in the variables' descriptions.
    ``dataset``: an ``xarray.Dataset`` or a
    :class:`~impactmaps.maps.files.data_io.MapArrays`.
    """
    return str(dataset.attrs.get("contact_law", "linear"))


class Axis(NamedTuple):
    """One axis of a map: its coordinate name and its description (``long_name``)."""

    name: str
    long_name: str


class PointPlan(NamedTuple):
    """How one map point is answered (:meth:`MapFamily.plan`).

    ``method`` None: ``unresolved`` (no model vouches for the point). ``asymptote`` a dict
    of map scalars: the point is that exact answer (with its method code and error
    columns). Otherwise the modal runs under the accuracy control, ``method`` naming the
    model (a :data:`~impactmaps.maps.compute.points.METHODS` entry).
    """

    method: str | None
    asymptote: dict | None = None


@dataclass(frozen=True)
class Interpolation:
    """How a family's lookups interpolate and bound their error.

    Attributes
    ----------
    reach : int
        Neighbours each side over which a second difference is the largest
        (:func:`impactmaps.maps.read.interpolator.interpolation_error`).
    safety : float
        Factor on the leading-order interpolation error ``h² |f''| / 8``.
    band_safety : float
        Factor on the whole band (own error + interpolation estimate) of a cube lookup.
    """

    reach: int = 2
    safety: float = 5.0
    band_safety: float = 1.0


class MapFamily:
    """One contact law's normalised maps (see the module docstring). Subclass and register.

    Attributes
    ----------
    name : str
        The map law, e.g. ``"hertz"`` (the ``contact_law`` attribute of its maps, their
        file suffix).
    axes : tuple of Axis
        Every axis of a point, slowest first; the last two are always ``lambda_`` and
        ``zeta`` (a (ζ, λ) family has just those two; an elastic-plastic one ``beta`` first).
    variables : dict
        The map's variables (:data:`RESULT_VARIABLES` layout), the family's descriptions.
    errors : dict
        The interpolated quantities of a lookup → the name of their error variable.
    interpolation : Interpolation
    shipped : dict
        (structure kind, theory) → structure name of the maps the package ships.
    law_in_description : bool
        Whether the law is a key of a sweep's description (the linear family's
        fingerprints predate it: False).
    law_revision : int
        The revision of the family's contact law (:attr:`ContactLaw.revision`); above 1 it
        is a key of a sweep's description, so its fingerprint changes with the law.
    title, method_text : str
        The ``title`` and ``method`` attributes of its maps.
    classifies : bool
        Whether its points have regimes (:meth:`infinite_peak`, :meth:`quasi_static_peak`).
    tile_lattice : dict
        Axis name → Δ log10 of the global lattice of its on-demand tiles
        (:mod:`impactmaps.maps.compute.tiles`), every axis.
    patch_loadable : bool
        Whether its points can be loaded over the contact patch (a family of one patch
        number P, ``with_patch``); the registered family itself is point-loaded.
    law_in_file_name : bool
        Whether its map files carry the law after the structure's name (:meth:`file_stem`;
        the linear maps' names predate the other laws: False).
    exact_command : str
        The command that answers one of its points exactly, named where a lookup refuses.
    scaled_by_contact_frequency : bool
        Whether F̄max = F_max/(m_i V0 ω) with ω = sqrt(K/m_i) of a contact stiffness K the
        user gives (:meth:`~impactmaps.maps.read.lookup.LookupResult.peak_force`).
    fmax_at_most_one : bool
        Whether F̄max ≤ 1 holds for every point (a chart's force axis ends at 1.05).
    closed_form_asymptotes : bool
        Whether its regimes' asymptotes are the closed forms a chart draws on any grid
        (the linear law's); otherwise a chart draws the peaks its map stores.
    labels : dict
        ``"zeta"``, ``"lambda"``, ``"fmax"`` (axis labels of its charts), ``"contact"``
        (the contact in a chart title, ``""`` for none), ``"quasi_static"`` (the legend of the
        stored quasi-static peaks), ``"table"`` (the header of its markdown lookup table),
        ``"zeta_name"``, ``"lambda_name"`` (the numbers in words, for messages).
    axis_ranges : dict
        Axis name → (low, high), the closed range of values a point can be realised at: beyond
        ζ ∈ [1e-9, 1e6], λ ∈ [1e-9, 1e9] the realised impactor's mass or contact frequency under-
        or overflows (ζ = 1e-300 gave a zero mass, λ = 1e300 a zero contact frequency; measured
        on beam-ss: every run answers inside); an elastic-plastic family adds β. An axis
        without an entry takes any positive value.
    chart_zeta_max, chart_lambda_min : float
        The range a chart of the family accepts: beyond ``chart_zeta_max`` its asymptotes
        stop answering (the linear infinite beam's closed form loses its root near ζ = 1e250
        and its peak is below 1e-4 beyond 1e6), below ``chart_lambda_min`` (inclusive) its
        quasi-static peak does.
    """

    name: ClassVar[str]
    axes: ClassVar[tuple[Axis, ...]]
    variables: ClassVar[dict] = RESULT_VARIABLES
    errors: ClassVar[dict] = {"fmax_normalised": "fmax_error"}
    interpolation: ClassVar[Interpolation] = Interpolation()
    shipped: ClassVar[dict] = {}
    law_in_description: ClassVar[bool] = True
    law_revision: ClassVar[int] = 1
    title: ClassVar[str] = "impactmaps normalised impact map"
    classifies: ClassVar[bool] = False
    tile_lattice: ClassVar[dict] = {"zeta": 0.05, "lambda_": 0.1}
    patch_loadable: ClassVar[bool] = False
    law_in_file_name: ClassVar[bool] = True
    exact_command: ClassVar[str] = "impactmaps simulate on a case file"
    scaled_by_contact_frequency: ClassVar[bool] = False
    fmax_at_most_one: ClassVar[bool] = True
    closed_form_asymptotes: ClassVar[bool] = False
    axis_ranges: ClassVar[dict] = {"zeta": (1.0e-9, 1.0e6), "lambda_": (1.0e-9, 1.0e9)}
    chart_zeta_max: ClassVar[float] = 1.0e6
    chart_lambda_min: ClassVar[float] = 0.0
    labels: ClassVar[dict] = {
        "zeta": "loss factor ζ", "lambda": "relative stiffness λ", "contact": "", "quasi_static": "quasi-static",
        "zeta_name": "loss factor ζ", "lambda_name": "relative stiffness λ",
        "fmax": r"normalised maximum force $\bar{F}_{max}$",
        "table": "# Normalised maximum force F̄max\n\nNearest computed grid point.\n\n"}

    def axis_range(self, name: str) -> tuple[float, float]:
        """The closed range (low, high) a point can be realised at on axis ``name``
        (:attr:`axis_ranges`); (0, ∞) for an axis without an entry (any positive value)."""
        return self.axis_ranges.get(name, (0.0, math.inf))

    def file_stem(self, structure_name: str) -> str:
        """File name (without its suffix) of the family's map of a structure:
        ``plate-ssss-kirchhoff-hertz``, or the structure's name alone (:attr:`law_in_file_name`)."""
        return f"{structure_name}-{self.name}" if self.law_in_file_name else structure_name

    @property
    def method_text(self) -> str:
        """The ``method`` attribute of the family's maps."""
        return f"modal impact solver (exact-step integrator, residual flexibility), {self.name} contact"

    @property
    def axis_names(self) -> tuple[str, ...]:
        """Coordinate names of the axes, slowest first (``(..., "lambda_", "zeta")``)."""
        return tuple(axis.name for axis in self.axes)

    @property
    def extra_axes(self) -> tuple[Axis, ...]:
        """The axes before (λ, ζ) (β of an elastic-plastic family)."""
        return self.axes[:-2]

    def describes(self, law) -> bool:
        """Whether a contact law's impacts are points of this family; ``ValueError`` with the
        reason for a law of the family's kind that its maps do not describe (default False)."""
        return False

    # -- points -----------------------------------------------------------------------
    def check(self, structure, target, settings) -> None:
        """Refuse a structure or settings the family cannot map (``ValueError``); default none."""

    def uses_table(self) -> bool:
        """Whether the points truncate the structure's basis table (default True)."""
        return True

    def realise_points(self, target, points) -> list:
        """The impacts realising ``points`` on ``target`` (each point ``(…, ζ, λ)``: the extra
        axes' values, then ζ and λ); default one :meth:`realise` each."""
        return [self.realise(target, point) for point in points]

    def realise(self, target, point) -> Any:
        """The impact realising one point on ``target``: an object with ``law``, ``mass``,
        ``velocity`` [SI], ``omega`` (contact frequency [rad/s], what the cut-off is a
        multiple of) and ``reflection`` (first wave return in the family's time unit)."""
        raise NotImplementedError

    def point_coordinates(self, point) -> dict:
        """The coordinates of a point as map variables (``{"zeta": …, "lambda_": …}`` …)."""
        *extra, zeta, lam = point
        names = [axis.name for axis in self.extra_axes]
        return dict(zip(names, (float(v) for v in extra))) | {"zeta": float(zeta), "lambda_": float(lam)}

    def moved(self, point, zeta_factor: float):
        """The point with ζ scaled by ``zeta_factor`` (the sensitive points' perturbed runs)."""
        *extra, zeta, lam = point
        return (*extra, zeta * zeta_factor, lam)

    def plan(self, target, realised, point, cap: float, settings) -> PointPlan:
        """How the point is answered (:class:`PointPlan`)."""
        raise NotImplementedError

    def scaled(self, result, realised):
        """A modal run read in the family's scales: an object with ``fmax_normalised``,
        ``impacts`` and ``normalised_summary()`` (default: the run itself)."""
        return result

    def companion_errors(self, runs: list, status: int, levels: int) -> dict:
        """Error variables of quantities besides F̄max from the runs of one point (default none)."""
        return {}

    def unresolved_extras(self) -> dict:
        """Values of the family's own variables at an ``unresolved`` point (default none)."""
        return {}

    def runner(self, target, table, cap: float, point, realised, runs: list):
        """``run(settings, zeta_factor)`` of one point, or None for the default table runner
        (:func:`impactmaps.maps.compute.points.table_runner`)."""
        return None

    # -- regimes ------------------------------------------------------------------------
    def infinite_peak(self, loss_factor, kind: str):
        """F̄max of the infinite structure of ``kind`` at ζ [-] (families that classify)."""
        raise ValueError(f"the {self.name} maps have no regimes")

    def quasi_static_peak(self, relative_stiffness):
        """F̄max of the quasi-static spring at λ [-] (families that classify)."""
        raise ValueError(f"the {self.name} maps have no regimes")

    def asymptote_peaks(self, kind: str, loss_factors, relative_stiffnesses) -> dict:
        """The :data:`ASYMPTOTE_PEAK_VARIABLES` a map of this family stores for a structure of
        ``kind`` on its grid (ζ values, λ values) [-]: name → values along its axis. What the
        map's lookups judge their regimes by, computed once when the map is built; a family
        without regimes stores none ({})."""
        if not self.classifies:
            return {}
        return {"infinite_structure_peak": np.asarray(self.infinite_peak(loss_factors, kind), float),
                "quasi_static_peak": np.asarray(self.quasi_static_peak(relative_stiffnesses), float)}


_REGISTRY: dict[str, MapFamily] = {}
#: The built-in families: map law → the module that defines and registers it (imported on first use).
_BUILT_IN = {"linear": "impactmaps.maps.compute.linear_points", "hertz": "impactmaps.maps.compute.hertz_points",
             "yc": "impactmaps.maps.compute.plastic_points", "stronge": "impactmaps.maps.compute.plastic_points",
             "epp": "impactmaps.maps.compute.plastic_points"}


def register_map_family(family: MapFamily) -> MapFamily:
    """Register a family object under its ``name`` (``ValueError`` if another one has it)."""
    axes = family.axis_names
    if axes[-2:] != ("lambda_", "zeta") or len(set(axes)) != len(axes):
        raise ValueError(f"map family {family.name!r}: its axes {axes} must end with 'lambda_', 'zeta'")
    if family.name in _REGISTRY and type(_REGISTRY[family.name]) is not type(family):
        raise ValueError(f"map family name {family.name!r} is already registered")
    _REGISTRY[family.name] = family
    return family


def available_map_families() -> tuple[str, ...]:
    """Names of the families: the built-in ones (linear, hertz, then the elastic-plastic ones),
    then those registered since, in registration order."""
    return tuple(dict.fromkeys([*_BUILT_IN, *_REGISTRY]))


def map_family(name) -> MapFamily:
    """The family ``name`` (a family object is returned as is; a built-in one's module is imported
    the first time it is asked for); ``ValueError`` if unknown."""
    if isinstance(name, MapFamily):
        return name
    require_choice("law", name, available_map_families())
    if name not in _REGISTRY:
        importlib.import_module(_BUILT_IN[name])  # registers it
    return _REGISTRY[name]
