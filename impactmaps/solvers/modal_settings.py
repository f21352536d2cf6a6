"""Settings and facts of a modal run: :class:`ModalSettings` (the numerical settings with
their ranges), :class:`ModalDetails`, the reference contact stiffness that sets the
contact frequency, and which load (point or patch) a run takes.
"""

from __future__ import annotations

import functools
from dataclasses import asdict, dataclass, replace


from .._checks import require_choice, require_flag, require_in_range, require_positive, require_whole
from ..contact.base import ContactLaw

__all__ = ["ModalSettings", "ModalDetails", "ConvergenceWarning", "DEFAULT_SETTINGS", "CONTACT_PATCHES",
           "CONTACT_PHASES", "MAX_CUTOFF_RATIO", "MAX_MIN_MODES", "MAX_EVENTS", "CORNER_MULTIPLE",
           "CORNER_MAX_MODES", "corner_ratios", "patch_cutoff_ratio_for",
           "with_corner_cutoff"]

#: Loads the modal solver can apply: "auto" (the default) — the patch on shear-deformable
#: targets that support it (Mindlin SSSS plates), the point load elsewhere; "point" — at
#: the impact point; "hertz-peak" — as a Hertz pressure over the contact disc at the peak
#: indentation (targets with ``supports_contact_patch``).
CONTACT_PATCHES = ("auto", "point", "hertz-peak")
#: How the modal solver integrates a contact (:attr:`ModalSettings.contact_phase`).
CONTACT_PHASES = ("auto", "exact", "sampled")
#: Largest ``cutoff_ratio`` and ``patch_cutoff_ratio``: modes 10⁴ times above the contact
#: frequency respond statically (the residual compliance carries them); the convergence
#: check's refinement stops doubling there.
MAX_CUTOFF_RATIO = 1e4
#: Largest ``min_modes`` (the refinement stops doubling there).
MAX_MIN_MODES = 100_000
#: Largest ``max_events``: the kernel allocates the contact-interval table whole (16 B each).
MAX_EVENTS = 10_000_000
#: The patch cut-off is never below this many times the contact's corner frequency
#: ``K/c = 2 ζ_p ω`` (the contact spring against the plate's local impedance ``c = 8 sqrt(ρh D*)``;
#: :func:`patch_cutoff_ratio_for`; measured in docs/plates_any_edges.rst, "The patch cut-off of
#: heavy impactors").
CORNER_MULTIPLE = 2.0
#: Most modes (all of the plate's, not only those the impact excites: a centre impact on a
#: symmetric plate excites about a quarter) the heavy-impactor rule raises a patch cut-off to:
#: beyond, the cut-off stops on a
#: fixed ladder below the corner's (ratios ``wanted · 2^(−k/4)``) and the run warns
#: (:func:`corner_ratios`); a very thin plate under a heavy impactor would otherwise integrate
#: tens of thousands of modes for minutes.
CORNER_MAX_MODES = 20_000

@dataclass(frozen=True)
class ModalDetails:
    """Extras of a modal run (``ImpactResult.details``): ``steps`` the integrator took [-] and
    ``contact_phase`` (``"exact"`` or ``"sampled"``, see :attr:`ModalSettings.contact_phase`).
    """

    steps: int
    contact_phase: str

    def summary(self) -> dict:
        """The details as JSON-ready scalars."""
        return {"steps": int(self.steps), "contact_phase": self.contact_phase}


class ConvergenceWarning(UserWarning):
    """A result moved by more than the tolerance when the model was refined."""


@dataclass(frozen=True)
class ModalSettings:
    """Numerical settings of the modal solver (all dimensionless).

    Attributes
    ----------
    cutoff_ratio : float
        Integrate modes with ω_j ≤ ``cutoff_ratio`` · ω (contact frequency); in
        (0, :data:`MAX_CUTOFF_RATIO`].
    patch_cutoff_ratio : float
        The same for a run under the contact patch (``contact_patch``), whose modal
        transform suppresses the high modes (convergence: ``docs/contact_patch.rst``);
        :func:`~impactmaps.solvers.modal.simulate` raises it on a plate struck by a heavy
        impactor, whose contact force holds frequencies far above ω
        (:func:`patch_cutoff_ratio_for`).
    min_modes : int
        Integrate at least this many participating modes; in [0, :data:`MAX_MIN_MODES`].
    residual_flexibility : bool
        Add the static compliance of the dropped modes in series with the contact.
    time_step_ratio : float
        Upper bound of ω·Δt.
    resolve_ratio : float
        Upper bound of ω_top·Δt (ω_top: highest coupled frequency in contact), unless
        the force's content allows a longer step (``force_resolution``).
    force_resolution : float
        Tolerated interpolation error of the structural oscillations of the contact
        force, in units of m_i V0 ω (:func:`content_time_step`); 0 always resolves ω_top.
    max_time_ratio : float
        Time limit in units of 1/ω.
    max_events : int
        Most contacts a run follows, in [1, :data:`MAX_EVENTS`]; a run with more stops
        there, with a warning and ``time_limit_reached`` set.
    check_convergence : bool
        Re-run with twice the cut-off and half the step and warn
        (:class:`ConvergenceWarning`) if F̄max moves by more than ``tolerance``.
    tolerance : float
        Convergence tolerance on F̄max.
    step_scale : float
        Factor in (0, 1] applied to the automatically chosen time step after every rule,
        the stability cap included (:meth:`refined` halves it).
    contact_patch : {"auto", "point", "hertz-peak"}
        ``"point"``: the force acts at the impact point. ``"hertz-peak"``: on targets
        that support it (SSSS plates) and with a contact law that has a geometry
        (:func:`impactmaps.contact.geometry.contact_radius_function`), a Hertz pressure over the contact disc of the
        peak indentation, found by fixed-point iteration (to :data:`PATCH_TOLERANCE`).
        ``"auto"`` (default): ``"hertz-peak"`` on Mindlin SSSS plates, whose point-load
        peak force never converges in the cut-off; the point load elsewhere
        (``docs/contact_patch.rst``).
    contact_phase : {"auto", "exact", "sampled"}
        How a contact is integrated. ``"exact"``: through the coupled modes of a linear
        contact (linear laws on at most :data:`COUPLED_MAX_MODES` undamped modes,
        otherwise sampled); ``"sampled"``: the exact-step scheme with the force sampled
        once per step; ``"auto"``: the exact phase where it costs less. A forced
        ``time_step`` always samples.
    """

    cutoff_ratio: float = 40.0
    patch_cutoff_ratio: float = 20.0
    min_modes: int = 4
    residual_flexibility: bool = True
    time_step_ratio: float = 0.0125
    resolve_ratio: float = 0.2
    force_resolution: float = 1e-5
    max_time_ratio: float = 5000.0
    max_events: int = 1000
    check_convergence: bool = False
    tolerance: float = 1e-3
    step_scale: float = 1.0
    contact_patch: str = "auto"
    contact_phase: str = "auto"

    def __post_init__(self):
        require_in_range("cutoff_ratio", self.cutoff_ratio, 0.0, MAX_CUTOFF_RATIO, low_inclusive=False)
        require_in_range("patch_cutoff_ratio", self.patch_cutoff_ratio, 0.0, MAX_CUTOFF_RATIO, low_inclusive=False)
        for name in ("residual_flexibility", "check_convergence"):
            require_flag(name, getattr(self, name))
        for name in ("min_modes", "max_events"):
            require_whole(name, getattr(self, name))
        require_in_range("min_modes", self.min_modes, 0, MAX_MIN_MODES)
        require_in_range("time_step_ratio", self.time_step_ratio, 0, 1.0, low_inclusive=False)
        require_in_range("resolve_ratio", self.resolve_ratio, 0, 2.0, low_inclusive=False)
        require_in_range("force_resolution", self.force_resolution, 0, 1e-2)
        require_positive("max_time_ratio", self.max_time_ratio)
        require_in_range("max_events", self.max_events, 1, MAX_EVENTS)
        require_positive("tolerance", self.tolerance)
        require_in_range("step_scale", self.step_scale, 0.0, 1.0, low_inclusive=False)
        require_choice("contact_patch", self.contact_patch, CONTACT_PATCHES)
        require_choice("contact_phase", self.contact_phase, CONTACT_PHASES)

    def refined(self) -> "ModalSettings":
        """Settings with twice the cut-off, twice the modes and half the time step (the
        cut-off and the modes at most :data:`MAX_CUTOFF_RATIO` and :data:`MAX_MIN_MODES`)."""
        return _refined(self)


@functools.lru_cache(maxsize=256)
def _refined(settings: ModalSettings) -> ModalSettings:
    """:meth:`ModalSettings.refined` (a pure function of frozen settings, cached: every map
    point asks it once or twice, of a handful of distinct settings)."""
    return replace(
        settings,
        cutoff_ratio=min(2 * settings.cutoff_ratio, MAX_CUTOFF_RATIO),
        patch_cutoff_ratio=min(2 * settings.patch_cutoff_ratio, MAX_CUTOFF_RATIO),
        min_modes=min(2 * settings.min_modes, MAX_MIN_MODES),
        step_scale=settings.step_scale / 2,
        check_convergence=False,
    )


DEFAULT_SETTINGS = ModalSettings()

def settings_dict(settings: ModalSettings) -> dict:
    """``asdict(settings)`` as a fresh dict (its items are cached per settings value)."""
    return dict(_settings_items(settings))


@functools.lru_cache(maxsize=64)
def _settings_items(settings: ModalSettings) -> tuple:
    """The fields of frozen, hashable ``settings`` as (name, value) pairs."""
    return tuple(asdict(settings).items())


def linear_stiffness(law: ContactLaw) -> float:
    """K [N/m] if ``law`` is linear (the integrator then solves the contact in closed
    form), else 0. The one place that asks whether a law is linear."""
    return law.linear_stiffness or 0.0


def uses_patch(target, contact_patch: str) -> bool:
    """Whether ``contact_patch`` asks for the Hertz patch on ``target`` and it supports one."""
    if not getattr(target, "supports_contact_patch", False):
        return False
    if contact_patch == "auto":  # where the point load has no converged answer (a Mindlin plate)
        return bool(getattr(target, "point_load_diverges", False))
    return contact_patch == "hertz-peak"


def patch_cutoff_ratio_for(settings: ModalSettings, target, impactor_mass: float, contact_stiffness: float) -> float:
    """The cut-off ratio [-] of a run under the contact patch on ``target``:
    ``max(patch_cutoff_ratio, CORNER_MULTIPLE · ω_c/ω)`` (at most :data:`MAX_CUTOFF_RATIO`).

    ``ω_c = K/c`` is the corner frequency of the contact stiffness ``contact_stiffness`` K [N/m]
    against the local impedance ``c = 8 sqrt(ρh D*)`` of a plate, ``ω_c/ω = 2 ζ_p`` with ζ_p the
    plate loss factor for ``impactor_mass`` [kg] (:meth:`Plate.loss_factor
    <impactmaps.targets.plates.plate.Plate.loss_factor>`): a heavy impactor (ζ_p ≫ 1) makes a
    force whose content reaches far above ω, and a cut-off below ω_c leaves it to the static
    residual (docs/plates_any_edges.rst, "The patch cut-off of heavy impactors"). Targets other
    than plates (none takes a patch) keep ``patch_cutoff_ratio``. A ratio this returns gives
    itself again (and so does twice it, the convergence check's).
    """
    return corner_ratios(settings, target, impactor_mass, contact_stiffness)[0]


def corner_ratios(settings: ModalSettings, target, impactor_mass: float, contact_stiffness: float) -> tuple:
    """(the patch cut-off ratio a run uses, the one the corner asks for) [-]: the second is
    ``max(patch_cutoff_ratio, CORNER_MULTIPLE · ω_c/ω)`` (at most :data:`MAX_CUTOFF_RATIO`);
    the first equals it unless ``target`` has more than :data:`CORNER_MAX_MODES` modes below
    it, then the largest of ``wanted · 2^(−k/4)`` within that count (never below
    ``patch_cutoff_ratio``). A target that can never have more than :data:`CORNER_MAX_MODES`
    modes (:meth:`~impactmaps.targets.base.Target.mode_count_bound`: the Ritz plates, whose
    largest basis has at most 3468 unknowns) is not counted: counting took the eigen-solution of
    its largest basis."""
    import math

    ratio = float(settings.patch_cutoff_ratio)
    if getattr(target, "kind", None) != "plate":
        return ratio, ratio
    corner = 2.0 * float(target.loss_factor(impactor_mass, contact_stiffness))
    wanted = max(ratio, min(CORNER_MULTIPLE * corner, MAX_CUTOFF_RATIO))
    bound = getattr(target, "mode_count_bound", lambda: math.inf)()
    if bound <= CORNER_MAX_MODES:  # never more modes than the budget: the loop below stops at k = 0
        return wanted, wanted
    omega = math.sqrt(contact_stiffness / impactor_mass)
    used = wanted
    for k in range(200):
        used = wanted * 2.0 ** (-k / 4)
        if used <= ratio or target.mode_count(used * omega, limit=CORNER_MAX_MODES) <= CORNER_MAX_MODES:
            break
    return max(ratio, used), wanted


def with_corner_cutoff(settings: ModalSettings, target, impactor_mass: float, contact_stiffness: float) -> ModalSettings:
    """``settings`` with ``patch_cutoff_ratio`` raised to :func:`patch_cutoff_ratio_for` (the same
    object where the rule does not raise it)."""
    ratio = patch_cutoff_ratio_for(settings, target, impactor_mass, contact_stiffness)
    return settings if ratio == settings.patch_cutoff_ratio else replace(settings, patch_cutoff_ratio=ratio)
