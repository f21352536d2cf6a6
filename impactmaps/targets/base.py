"""What a target must supply to the impact solvers.

A target is anything the sphere strikes. The modal solver needs only what the target
looks like *from the impact point*: its natural frequencies, the mass-normalised mode
shapes evaluated there, and the static compliance of the modes it leaves out
(:class:`ModalBasis`). The dimensionless framework needs the static point stiffness
(for λ) and the loss-factor formula of the structure type (for ζ).
"""

from __future__ import annotations

import math
import warnings

from abc import ABC, abstractmethod
from dataclasses import dataclass
from typing import ClassVar, NamedTuple

import numpy as np

from .map_structure import StructureKey, describing_structure, similarity_groups
from .options import CLASSICAL_THEORIES, DIVERGENT_POINT_LOAD_THEORIES

__all__ = ["InfiniteImpact", "ModalBasis", "dropped_compliance_sums", "Target", "RESIDUAL_ROUND_OFF",
           "PARTICIPATION_THRESHOLD", "DEGENERACY_TOLERANCE"]

#: Relative size (of the static compliance) of a negative residual compliance that is
#: treated as round-off and clipped to zero; anything more negative means wrong modes.
RESIDUAL_ROUND_OFF = 1e-9
#: Modes with ``φ_j² ≤ PARTICIPATION_THRESHOLD · max φ²`` do not take part in an impact.
PARTICIPATION_THRESHOLD = 1e-24
#: Modes whose frequencies differ by at most this fraction (and whose damping ratios are
#: equal) are one mode to the impact point (:meth:`ModalBasis.participating`). Their
#: frequencies are equal in exact arithmetic (the (m, n) and (n, m) pairs of a square plate,
#: the pairs of equal m² + n²); merged at 1e-9 they would drift apart by less than a
#: radian only after 10⁹/(2π) periods, far beyond any impact.
DEGENERACY_TOLERANCE = 1e-9


@dataclass(frozen=True)
class ModalBasis:
    """Modes of a target seen from the impact point.

    Attributes
    ----------
    frequencies : ndarray, shape (n,)
        Natural frequencies ω_j [rad/s], ascending; zero for rigid-body modes.
    participation : ndarray, shape (n,)
        Mass-normalised mode shapes at the impact point φ_j(x0) [kg^-1/2], so that the
        target deflection there is ``w_t = Σ φ_j q_j`` and ``q̈_j + ω_j² q_j = φ_j F``.
    residual_compliance : float
        Static compliance [m/N] at the impact point of the modes *not* retained
        (exact static compliance minus ``Σ φ_j²/ω_j²`` over retained elastic modes);
        added in series with the contact (residual-flexibility correction, spec 3.4).
    damping_ratios : ndarray, shape (n,)
        Modal viscous damping ratios [-] (default zeros).
    """

    frequencies: np.ndarray
    participation: np.ndarray
    residual_compliance: float = 0.0
    damping_ratios: np.ndarray | None = None

    def __post_init__(self):
        frequencies = np.ascontiguousarray(self.frequencies, dtype=float)
        participation = np.ascontiguousarray(self.participation, dtype=float)
        if frequencies.shape != participation.shape or frequencies.ndim != 1:
            raise ValueError(
                "frequencies and participation must be 1-D arrays of equal length, got "
                f"shapes {frequencies.shape} and {participation.shape}"
            )
        if np.any(~np.isfinite(frequencies)) or np.any(frequencies < 0):
            raise ValueError("frequencies must be finite and >= 0 [rad/s]")
        if not np.all(np.isfinite(participation)):
            raise ValueError("participation must be finite [kg^-1/2]")
        if not (np.isfinite(self.residual_compliance) and self.residual_compliance >= 0):
            raise ValueError(
                f"residual_compliance = {self.residual_compliance!r} is invalid: "
                "valid range is [0, inf) [m/N]"
            )
        damping = (
            np.zeros_like(frequencies)
            if self.damping_ratios is None
            else np.broadcast_to(np.asarray(self.damping_ratios, dtype=float), frequencies.shape).copy()
        )
        if np.any(damping < 0) or np.any(damping >= 1):
            raise ValueError("damping_ratios must lie in [0, 1)")
        object.__setattr__(self, "frequencies", frequencies)
        object.__setattr__(self, "participation", participation)
        object.__setattr__(self, "damping_ratios", damping)
        object.__setattr__(self, "_participating", False)

    @classmethod
    def from_validated(cls, frequencies, participation, residual_compliance, damping_ratios, *,
                       participating: bool = False) -> "ModalBasis":
        """A basis made of parts of an already validated one, without re-checking them.

        For the solvers' hot paths (truncating or filtering a validated basis); the
        arrays — frequencies [rad/s], participations [kg^-1/2], damping ratios [-] — must
        be float64, 1-D, of equal length, and satisfy the class invariants; the residual
        compliance is in m/N. ``participating``: the modes are known to be as
        :meth:`participating` leaves them (it then returns the basis itself at once).
        """
        basis = object.__new__(cls)
        object.__setattr__(basis, "frequencies", np.ascontiguousarray(frequencies))
        object.__setattr__(basis, "participation", np.ascontiguousarray(participation))
        object.__setattr__(basis, "residual_compliance", float(residual_compliance))
        object.__setattr__(basis, "damping_ratios", np.ascontiguousarray(damping_ratios))
        object.__setattr__(basis, "_participating", bool(participating))
        return basis

    @classmethod
    def from_modes(cls, frequencies, participation, static_compliance: float,
                   damping_ratios=None, *, retained_compliance: float | None = None) -> "ModalBasis":
        """The basis of some modes of a target whose exact static compliance is known.

        The residual compliance is ``static_compliance − retained`` [m/N], with
        ``retained = Σ φ_j²/ω_j²`` over the elastic modes given (:attr:`retained_compliance`)
        unless ``retained_compliance`` is passed (a Mindlin plate counts the classical
        compliance of its retained half-wave pairs). A negative residual smaller than
        :data:`RESIDUAL_ROUND_OFF` times the static compliance is round-off and set to 0.

        Parameters
        ----------
        frequencies, participation, damping_ratios
            As the attributes of :class:`ModalBasis` [rad/s], [kg^-1/2], [-].
        static_compliance : float
            Exact static point compliance [m/N] of the target at the impact point.
        retained_compliance : float, optional
            Static compliance [m/N] counted as carried by the given modes.

        Raises
        ------
        RuntimeError
            When the retained compliance exceeds the static one by more than round-off
            (the modes are wrong).
        """
        basis = cls(frequencies, participation, 0.0, damping_ratios)
        retained = basis.retained_compliance if retained_compliance is None else float(retained_compliance)
        residual = static_compliance - retained
        if residual < 0:
            if residual < -RESIDUAL_ROUND_OFF * static_compliance:
                raise RuntimeError(
                    f"retained modal compliance {retained:.12e} m/N exceeds the static "
                    f"compliance {static_compliance:.12e} m/N: the modes are wrong")
            residual = 0.0
        return cls.from_validated(basis.frequencies, basis.participation, residual, basis.damping_ratios)

    def truncate(self, max_frequency: float, min_modes: int = 1) -> "ModalBasis":
        """The modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``, if present).

        The static compliance ``φ_j²/ω_j²`` of the elastic modes left out is added to the
        residual compliance, so retained + residual stays the target's static compliance
        (residual-flexibility correction). The frequencies must be ascending. The left-out
        compliances are summed from the highest mode down (smallest terms first,
        :func:`dropped_compliance_sums`).
        """
        count = self.cutoff_count(max_frequency, min_modes)
        if count == self.size:
            return self
        tail = dropped_compliance_sums(self.frequencies[count:], self.participation[count:])
        return self.head(count, float(tail[-1]))

    def cutoff_count(self, max_frequency: float, min_modes: int = 1) -> int:
        """How many modes :meth:`truncate` keeps: those with ω_j ≤ ``max_frequency`` [rad/s],
        at least ``min_modes`` and at most all."""
        frequencies = self.frequencies
        # the array's own searchsorted: np.searchsorted's answer without its Python wrapper
        count = int(frequencies.searchsorted(max_frequency, side="right"))
        return min(max(count, int(min_modes)), frequencies.size)

    def head(self, count: int, dropped_compliance: float) -> "ModalBasis":
        """The first ``count`` modes, with ``dropped_compliance`` [m/N] — the static
        compliance of the others (:func:`dropped_compliance_sums`) — added to the residual."""
        # the head of a participating basis is one (its largest φ² is not larger; a
        # degenerate group has one frequency, so a head keeps it whole or not at all)
        return ModalBasis.from_validated(self.frequencies[:count], self.participation[:count],
                                         dropped_compliance + self.residual_compliance,
                                         self.damping_ratios[:count], participating=self._participating)

    def participating(self) -> "ModalBasis":
        """The modes as the impact point sees them (same residual compliance).

        A mode with ``φ_j² ≤`` :data:`PARTICIPATION_THRESHOLD` ``· max φ²`` is never
        excited by the contact force (e.g. antisymmetric modes at a centre impact); it is
        dropped and its (negligible) compliance is not moved to the residual. Modes of one
        frequency and damping ratio (degenerate, :data:`DEGENERACY_TOLERANCE`) are merged
        into one of participation ``sqrt(Σ φ_j²)``: driven by the same contact force they
        move as one coordinate ``Q = Σ φ_j q_j / sqrt(Σ φ_j²)``, exactly, and the impact
        point's deflection is ``sqrt(Σ φ_j²) Q`` (a square plate struck at its centre has
        ~3 modes per distinct frequency; the solver's cost is per mode). Only neighbours
        merge (the bases of the targets are in ascending order).
        """
        if self._participating:
            return self
        merged = self.__dict__.get("_participating_basis")
        if merged is None:  # computed once per basis (a frozen value: its arrays are not changed)
            merged = self._merge_participating()
            if merged is not self:
                object.__setattr__(self, "_participating_basis", merged)
        return merged

    def _merge_participating(self) -> "ModalBasis":
        squares = self.participation**2
        significant = squares > PARTICIPATION_THRESHOLD * max(float(np.max(squares, initial=0.0)), 1e-300)
        frequencies, damping = self.frequencies[significant], self.damping_ratios[significant]
        starts = _degenerate_group_starts(frequencies, damping)
        if starts.size == frequencies.size:
            if np.all(significant):
                object.__setattr__(self, "_participating", True)  # a flag that changes no answer
                return self
            return ModalBasis.from_validated(frequencies, self.participation[significant],
                                             self.residual_compliance, damping, participating=True)
        # group sums of φ² in order (np.add.reduceat: one pass, deterministic)
        merged = np.sqrt(np.add.reduceat(squares[significant], starts))
        return ModalBasis.from_validated(frequencies[starts], merged, self.residual_compliance, damping[starts],
                                         participating=True)

    @property
    def size(self) -> int:
        """Number of retained modes."""
        return int(self.frequencies.size)

    @property
    def retained_compliance(self) -> float:
        """Static compliance [m/N] of the retained elastic modes, ``Σ φ_j²/ω_j²``."""
        elastic = self.frequencies > 0
        return float(np.sum(self.participation[elastic] ** 2 / self.frequencies[elastic] ** 2))


def _degenerate_group_starts(frequencies: np.ndarray, damping_ratios: np.ndarray) -> np.ndarray:
    """Indices where a group of degenerate modes starts (frequencies [rad/s]): a mode joins
    the group before it when its frequency lies within :data:`DEGENERACY_TOLERANCE` of the
    group's first and its damping ratio equals the previous mode's (only neighbours merge:
    in a basis not in ascending order, equal frequencies apart stay apart).

    Vectorised: the groups of neighbours that are close are the answer when every mode lies
    within the tolerance of its group's first (the usual case); a chain of close neighbours
    that drifts further is split by the sequential rule (:func:`_split_drifting_groups`)."""
    n = frequencies.size
    if n < 2:
        return np.arange(n)
    close = (np.abs(frequencies[1:] - frequencies[:-1]) <= DEGENERACY_TOLERANCE * frequencies[1:]) & (
        damping_ratios[1:] == damping_ratios[:-1])
    if not np.any(close):
        return np.arange(n)
    starts = np.flatnonzero(np.concatenate(([True], ~close)))
    first = frequencies[np.repeat(starts, np.diff(np.append(starts, n)))]
    if np.all(np.abs(frequencies - first) <= DEGENERACY_TOLERANCE * frequencies):
        return starts
    return _split_drifting_groups(frequencies, close)


def _split_drifting_groups(frequencies: np.ndarray, close: np.ndarray) -> np.ndarray:
    """The sequential grouping rule of :func:`_degenerate_group_starts`, mode by mode."""
    starts = [0]
    for j in range(1, frequencies.size):
        if not close[j - 1] or abs(frequencies[j] - frequencies[starts[-1]]) > DEGENERACY_TOLERANCE * frequencies[j]:
            starts.append(j)
    return np.asarray(starts, dtype=np.intp)


def dropped_compliance_sums(frequencies: np.ndarray, participation: np.ndarray) -> np.ndarray:
    """Static compliances [m/N] of the modes from the highest down, summed one by one.

    Element ``i`` is ``Σ φ_j²/ω_j²`` over the last ``i + 1`` modes (rigid-body modes,
    ω_j = 0, count 0), added in order from the highest mode down — smallest terms first;
    ``np.cumsum`` adds sequentially, so element ``i`` has the same bits as the last
    element of the sums of those ``i + 1`` modes alone. :meth:`ModalBasis.truncate` takes
    the last element over the modes it drops; a table truncated many times computes the
    sums once (:class:`impactmaps.maps.family.structures.BasisTable`).

    Parameters
    ----------
    frequencies : ndarray, shape (n,)
        ω_j [rad/s], ≥ 0.
    participation : ndarray, shape (n,)
        φ_j [kg^-1/2].

    Returns
    -------
    ndarray, shape (n,)
    """
    compliance = np.zeros_like(frequencies)
    elastic = frequencies > 0
    compliance[elastic] = participation[elastic] ** 2 / frequencies[elastic] ** 2
    return np.cumsum(compliance[::-1])


class InfiniteImpact(NamedTuple):
    """Linear-contact impact on the infinite structure of a target's kind (normalised).

    Forces by ``m_i V0 ω``, times by ``1/ω`` and velocities by ``V0`` (ω the contact
    frequency sqrt(K/m_i)); exact until the first wave returns from a boundary.

    Attributes
    ----------
    peak_force : float
        F̄max [-].
    peak_time : float
        ω t of the peak [-].
    contact_time : float
        ω t_c of the separation [-] (NaN if the impactor never separates).
    rebound_velocity : float
        Impactor velocity at separation over V0 [-] (NaN if there is no separation).
    """

    peak_force: float
    peak_time: float
    contact_time: float
    rebound_velocity: float


class Target(ABC):
    """A struck structure: supplies modes at the impact point and its static stiffness.

    Subclasses are frozen dataclasses (SI units) with ``kind`` set to ``"beam"``,
    ``"plate"`` or ``"halfspace"``.
    """

    kind: ClassVar[str]

    @property
    def structure(self) -> str:
        """Deprecated: :attr:`kind`."""
        warnings.warn(f"{type(self).__name__}.structure is now .kind; the old name will be removed",
                      FutureWarning, stacklevel=2)
        return self.kind

    @abstractmethod
    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """All modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``).

        The returned basis carries the residual compliance of the modes left out.
        """

    @property
    def bounded_modes(self) -> bool:
        """True when the target's modes come from a model of bounded size (a Ritz plate, a
        finite-element beam, the half-space): no cut-off makes it build more than that
        model. False by default: the mode count grows without bound with the cut-off
        (Navier plates, closed-form beams) and :mod:`impactmaps.solvers.mode_budget`
        guards it."""
        return False

    def resolution_limit(self) -> float:
        """Highest natural frequency [rad/s] the target's largest model resolves.

        ``inf`` by default: the modes are exact at any cut-off (Navier plates, closed-form
        beams). A target of bounded size (:attr:`bounded_modes`) returns what its largest
        model resolves (a Ritz plate at its largest basis, a finite-element beam at its
        largest mesh); a cut-off above it is capped there, and
        :func:`impactmaps.solvers.modal.simulate` treats the run as capped (another model
        answers, or the capped basis is reported as such).
        """
        return math.inf

    def resolved_mode_count(self) -> int:
        """Number of modes below :meth:`resolution_limit` (0 when the limit is infinite): what
        the largest model can integrate. By default :meth:`mode_count` at the limit;
        a target whose count would need its largest eigen-solution may estimate it."""
        limit = self.resolution_limit()
        return int(self.mode_count(limit)) if math.isfinite(limit) else 0

    def mode_count(self, max_frequency: float, limit: int | None = None) -> int:
        """Number of modes with ω_j ≤ ``max_frequency`` [rad/s], participating or not.

        The modes :meth:`modes` returns at that cut-off (when it lies above the
        fundamental). Exact; once the count is certain to exceed ``limit``, counting may
        stop early and return a lower bound that exceeds ``limit``. This default builds
        the modes, which suits targets whose model has a bounded size (Ritz plates,
        finite-element beams, the half-space); targets whose mode count grows without
        bound (Navier plates, closed-form beams) count without building them.

        Parameters
        ----------
        max_frequency : float
            Cut-off ω_max [rad/s], ≥ 0.
        limit : int, optional
            Counting may stop once the count exceeds it (default: count everything).

        Returns
        -------
        int
        """
        basis = self.modes(float(max_frequency), min_modes=1)
        return int(np.searchsorted(basis.frequencies, float(max_frequency), side="right"))

    @abstractmethod
    def static_compliance(self) -> float:
        """Static point compliance 1/K_st [m/N] at the impact point, as used for λ."""

    def static_stiffness(self) -> float:
        """Static point stiffness K_st [N/m] at the impact point (spec 3.2, 3.3)."""
        return 1.0 / self.static_compliance()

    @abstractmethod
    def loss_factor(self, impactor_mass, contact_stiffness):
        """Loss factor ζ [-] of this structure type for impactor mass [kg] and K [N/m]."""

    @abstractmethod
    def impactor_mass_for(self, loss_factor, contact_stiffness):
        """Impactor mass m_i [kg] giving ``loss_factor`` ζ with contact stiffness K [N/m]."""

    @property
    def point_load_diverges(self) -> bool:
        """Whether the deflection under a point load is unbounded, so that a point-load peak
        force has no converged value in the mode cut-off (the contact patch answers): a
        target whose ``theory`` is one of :data:`~impactmaps.targets.options.DIVERGENT_POINT_LOAD_THEORIES`."""
        return getattr(self, "theory", None) in DIVERGENT_POINT_LOAD_THEORIES

    @property
    def has_classical_asymptote(self) -> bool:
        """Whether the closed-form infinite-structure solutions (:meth:`infinite_structure_peak`)
        hold for the target's theory (:data:`~impactmaps.targets.options.CLASSICAL_THEORIES`)."""
        return getattr(self, "theory", None) in CLASSICAL_THEORIES

    @property
    def section_depth(self) -> float | None:
        """Depth [m] of the structure in the impact direction (a beam's height, a plate's
        thickness); None (the default) when not known."""
        return None

    def distance_to_nearest_support(self) -> float:
        """Distance [m] from the impact point to the nearest clamped or simply supported
        boundary (∞, the default, without one). Finite structures override it."""
        return math.inf

    def thickness_shear_frequency(self) -> float | None:
        """The thickness-shear cut-off ω_s [rad/s] of a shear-deformable theory, above a
        fraction of which it stops holding (:mod:`impactmaps.targets.shear_range`); None
        (the default) for a theory without one."""
        return None

    def wave_return_distance(self) -> float:
        """Distance [m] from the impact point to the nearest boundary that reflects flexural
        waves back to it. Finite structures (beams, plates) override it."""
        raise NotImplementedError(f"{type(self).__name__} has no boundary")

    def flexural_group_velocity(self, angular_frequency):
        """Group velocity [m/s] of the flexural waves at ``angular_frequency`` ω [rad/s] in the
        classical (shear-rigid) theory, ``2 sqrt(ω) (D/m)^(1/4)`` with D/m the bending
        stiffness over the mass per length or area. Finite structures override it."""
        raise NotImplementedError(f"{type(self).__name__} has no flexural waves")

    def reflection_time(self, contact_frequency):
        """Normalised time ω d²/c [-] of the first wave return to the impact point.

        ``contact_frequency`` ω [rad/s] (may be an array); d the distance [m] to the
        boundary whose reflection comes back first and ``c = sqrt(bending stiffness /
        mass per length or area)`` [m²/s]. Finite structures (beams, plates) override it.
        """
        raise NotImplementedError(f"{type(self).__name__} has no wave-return time")

    def map_structure(self, *, patch_loaded: bool = False) -> StructureKey | None:
        """The reference structure whose normalised maps describe this target exactly, or None.

        :func:`impactmaps.targets.map_structure.describing_structure`: the isotropic,
        undamped unit-span beam or plate of the target's theory, supports, aspect, impact
        point (and slenderness, Poisson ratio where they matter) with the target's
        dimensionless groups; ``patch_loaded``: the impact is loaded over the contact patch.
        :meth:`map_structure_refusal` says why there is none.
        """
        return describing_structure(self, patch_loaded)[0]

    def map_structure_refusal(self, *, patch_loaded: bool = False) -> str | None:
        """Why no reference structure describes this target (:meth:`map_structure`), or None."""
        return describing_structure(self, patch_loaded)[1]

    def similarity_groups(self) -> dict:
        """The dimensionless groups that, with shape, supports and impact point, fix the target's
        normalised response (:func:`impactmaps.targets.map_structure.similarity_groups`)."""
        return similarity_groups(self)

    @classmethod
    def infinite_structure_peak(cls, loss_factor):
        """Normalised peak force F̄∞(ζ) [-] on the infinite structure of this kind.

        ``loss_factor`` ζ [-] may be an array. Finite structures override it.
        """
        raise NotImplementedError(f"{cls.__name__} has no infinite-structure asymptote")

    @classmethod
    def infinite_structure_impact(cls, loss_factor: float) -> InfiniteImpact:
        """The whole infinite-structure impact at one loss factor ζ [-] (:class:`InfiniteImpact`)."""
        raise NotImplementedError(f"{cls.__name__} has no infinite-structure asymptote")
