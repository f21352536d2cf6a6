"""What a map family is (its axes, points, variables and asymptotes) and the registry.

A map family is one contact law's normalised impact map; each is a :class:`MapFamily`
registered under its map law (``"linear"``, ``"hertz"``, ``"yc"``, …). The built-in
families are imported when first asked for (:func:`map_family`). Adding a family:
docs/map_families.rst.
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
    """The map law (its family's name) a map dataset was swept with; ``"linear"`` without the
    attribute. ``dataset``: an ``xarray.Dataset`` or a
    :class:`~impactmaps.maps.files.data_io.MapArrays`.
    """
    return str(dataset.attrs.get("contact_law", "linear"))


class Axis(NamedTuple):
    """One axis of a map: its coordinate name and its description (``long_name``)."""

    name: str
    long_name: str


class PointPlan(NamedTuple):
    """How one map point is answered (:meth:`MapFamily.plan`): ``method`` None is
    ``unresolved``; an ``asymptote`` dict is the point's exact answer; otherwise modal runs
    under the accuracy control, ``method`` naming the model.
    """

    method: str | None
    asymptote: dict | None = None


@dataclass(frozen=True)
class Interpolation:
    """How a family's lookups interpolate and bound their error: ``reach`` (neighbours each
    side over which a second difference is the largest), ``safety`` (factor on the
    leading-order error ``h² |f''| / 8``) and ``band_safety`` (factor on a cube lookup's band).
    """

    reach: int = 2
    safety: float = 5.0
    band_safety: float = 1.0


class MapFamily:
    """One contact law's normalised maps. Subclass and register.

    Attributes
    ----------
    name : str
        The map law, e.g. ``"hertz"`` (the ``contact_law`` attribute of its maps).
    axes : tuple of Axis
        Every axis of a point, slowest first; the last two are ``lambda_`` and ``zeta``.
    variables, errors : dict
        The map's variables (:data:`RESULT_VARIABLES` layout); interpolated quantity → its
        error variable.
    interpolation : Interpolation
    shipped : dict
        (structure kind, theory) → structure name of the shipped maps.
    law_in_description, law_in_file_name : bool
        Whether the law enters a sweep's description and the map files' names (linear: False).
    law_revision : int
        The law's :attr:`ContactLaw.revision`; above 1 it enters the fingerprint.
    title, method_text, exact_command : str
        The maps' ``title`` and ``method`` attributes; the command that answers a point exactly.
    classifies, patch_loadable, closed_form_asymptotes : bool
        Whether its points have regimes, can be patch-loaded, and have closed-form asymptotes.
    tile_lattice : dict
        Axis name → Δ log10 of the lattice of its on-demand tiles.
    scaled_by_contact_frequency, fmax_at_most_one : bool
        Whether F̄max = F_max/(m_i V0 ω) with a user-given K, and whether F̄max ≤ 1 always.
    labels : dict
        The texts of its charts, tables and messages (``"zeta"``, ``"lambda"``, ``"fmax"``, …).
    axis_ranges : dict
        Axis name → (low, high), the range a point can be realised at (ζ ∈ [1e-9, 1e6],
        λ ∈ [1e-9, 1e9]; no entry: any positive value).
    chart_zeta_max, chart_lambda_min : float
        The range a chart of the family accepts.
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
        "table": "# Normalised maximum force F̄max\n\nNearest computed grid point.\n\n",
        # what the shipped maps' structures are, where "table" says it ({structures})
        "structures": "impact at the centre, simply supported"}

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

    #: Whether a point whose cut-off a bounded Ritz plate cannot resolve is answered as
    #: ``simulate`` answers it (:func:`impactmaps.maps.compute.points.capped_resolvable`):
    #: on the modes up to what the basis resolves, checked by halving that cap.
    capped_points = False

    def uses_table(self) -> bool:
        """Whether the points truncate the structure's basis table (default True)."""
        return True

    def realise_points(self, target, points) -> list:
        """The impacts realising ``points`` on ``target`` (each point ``(…, ζ, λ)``: the extra
        axes' values, then ζ and λ); default one :meth:`realise` each."""
        return [self.realise(target, point) for point in points]

    def realise(self, target, point) -> Any:
        """The impact realising one point on ``target``: ``law``, ``mass``, ``velocity`` [SI],
        ``omega`` (contact frequency [rad/s]) and ``reflection`` (first wave return, family time unit).
        """
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
        """The :data:`ASYMPTOTE_PEAK_VARIABLES` stored for a structure of ``kind`` on the grid
        (ζ, λ values) [-]: name → values along its axis ({} without regimes).
        """
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
