"""What a target must supply to the impact solvers.

The modal solver needs the modes seen from the impact point (:class:`ModalBasis`); the
dimensionless framework needs the static point stiffness (λ) and the loss factor (ζ).
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
        Mass-normalised mode shapes at the impact point φ_j(x0) [kg^-1/2].
    residual_compliance : float
        Static compliance [m/N] at the impact point of the modes not retained.
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
        """A basis from parts of a validated one, without re-checking them (hot paths).

        Arrays as the attributes (float64, 1-D, equal length); ``participating``: the modes
        are already as :meth:`participating` leaves them.
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
        """The basis of some modes of a target whose exact static compliance [m/N] is known.

        The residual compliance is ``static_compliance − retained_compliance`` (default
        ``Σ φ_j²/ω_j²``); a negative residual within round-off is set to 0.

        Raises
        ------
        RuntimeError
            When the retained compliance exceeds the static one by more than round-off.
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
        """The modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``); the
        compliance of those left out moves to the residual."""
        count = self.cutoff_count(max_frequency, min_modes)
        if count == self.size:
            return self
        tail = dropped_compliance_sums(self.frequencies[count:], self.participation[count:])
        return self.head(count, float(tail[-1]))

    def cutoff_count(self, max_frequency: float, min_modes: int = 1) -> int:
        """How many modes :meth:`truncate` keeps."""
        frequencies = self.frequencies
        # the array's own searchsorted: np.searchsorted's answer without its Python wrapper
        count = int(frequencies.searchsorted(max_frequency, side="right"))
        return min(max(count, int(min_modes)), frequencies.size)

    def head(self, count: int, dropped_compliance: float) -> "ModalBasis":
        """The first ``count`` modes, ``dropped_compliance`` [m/N] added to the residual."""
        # the head of a participating basis is one (its largest φ² is not larger; a
        # degenerate group has one frequency, so a head keeps it whole or not at all)
        return ModalBasis.from_validated(self.frequencies[:count], self.participation[:count],
                                         dropped_compliance + self.residual_compliance,
                                         self.damping_ratios[:count], participating=self._participating)

    def participating(self) -> "ModalBasis":
        """The modes the impact point excites: modes with negligible φ_j dropped, degenerate
        neighbours merged into one of participation ``sqrt(Σ φ_j²)`` (exact)."""
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
    """Indices where a group of degenerate neighbouring modes starts (same damping,
    frequency within :data:`DEGENERACY_TOLERANCE` of the group's first)."""
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
    """Cumulative static compliances [m/N] ``Σ φ_j²/ω_j²`` of the last ``i + 1`` modes,
    summed from the highest mode down (rigid-body modes count 0)."""
    compliance = np.zeros_like(frequencies)
    elastic = frequencies > 0
    compliance[elastic] = participation[elastic] ** 2 / frequencies[elastic] ** 2
    return np.cumsum(compliance[::-1])


class InfiniteImpact(NamedTuple):
    """Linear-contact impact on the infinite structure of a target's kind (normalised).

    Forces by ``m_i V0 ω``, times by ``1/ω``, velocities by ``V0`` (ω = sqrt(K/m_i)).

    Attributes
    ----------
    peak_force : float
        F̄max [-].
    peak_time : float
        ω t of the peak [-].
    contact_time : float
        ω t_c of the separation [-] (NaN if the impactor never separates).
    rebound_velocity : float
        Impactor velocity at separation over V0 [-] (NaN if no separation).
    """

    peak_force: float
    peak_time: float
    contact_time: float
    rebound_velocity: float


class Target(ABC):
    """A struck structure (frozen dataclass, SI units; ``kind`` "beam", "plate" or "halfspace")."""

    kind: ClassVar[str]

    @property
    def structure(self) -> str:
        """Deprecated: :attr:`kind`."""
        warnings.warn(f"{type(self).__name__}.structure is now .kind; the old name will be removed",
                      FutureWarning, stacklevel=2)
        return self.kind

    @abstractmethod
    def modes(self, max_frequency: float, min_modes: int = 1) -> ModalBasis:
        """All modes with ω_j ≤ ``max_frequency`` [rad/s] (at least ``min_modes``), with residual compliance."""

    @property
    def bounded_modes(self) -> bool:
        """True when the modes come from a model of bounded size (Ritz plate, FE beam, half-space)."""
        return False

    def resolution_limit(self) -> float:
        """Highest natural frequency [rad/s] the target's largest model resolves (``inf`` by default)."""
        return math.inf

    def resolved_mode_count(self) -> int:
        """Number of modes below :meth:`resolution_limit` (0 when the limit is infinite)."""
        limit = self.resolution_limit()
        return int(self.mode_count(limit)) if math.isfinite(limit) else 0

    def mode_count_bound(self) -> float:
        """An upper bound [-] of every :meth:`mode_count` of the target, known without counting:
        ``inf`` by default (no bound); a model of bounded size gives its number of unknowns."""
        return math.inf

    def mode_count(self, max_frequency: float, limit: int | None = None) -> int:
        """Number of modes with ω_j ≤ ``max_frequency`` [rad/s], participating or not.

        Counting may stop early once the count exceeds ``limit`` (the result is then a
        lower bound above ``limit``).
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
        """Whether the point-load deflection is unbounded (theory in
        :data:`~impactmaps.targets.options.DIVERGENT_POINT_LOAD_THEORIES`)."""
        return getattr(self, "theory", None) in DIVERGENT_POINT_LOAD_THEORIES

    @property
    def has_classical_asymptote(self) -> bool:
        """Whether :meth:`infinite_structure_peak` holds for the target's theory."""
        return getattr(self, "theory", None) in CLASSICAL_THEORIES

    @property
    def section_depth(self) -> float | None:
        """Depth [m] in the impact direction (beam height, plate thickness); None if unknown."""
        return None

    def distance_to_nearest_support(self) -> float:
        """Distance [m] from the impact point to the nearest support (∞ without one)."""
        return math.inf

    def thickness_shear_frequency(self) -> float | None:
        """Thickness-shear cut-off ω_s [rad/s] of a shear-deformable theory; None otherwise."""
        return None

    def wave_return_distance(self) -> float:
        """Distance [m] to the nearest boundary reflecting flexural waves back to the impact point."""
        raise NotImplementedError(f"{type(self).__name__} has no boundary")

    def flexural_group_velocity(self, angular_frequency):
        """Classical flexural group velocity [m/s] at ``angular_frequency`` ω [rad/s]."""
        raise NotImplementedError(f"{type(self).__name__} has no flexural waves")

    def reflection_time(self, contact_frequency):
        """Normalised time ω d²/c [-] of the first wave return (``contact_frequency`` ω [rad/s])."""
        raise NotImplementedError(f"{type(self).__name__} has no wave-return time")

    def map_structure(self, *, patch_loaded: bool = False) -> StructureKey | None:
        """The reference structure whose normalised maps describe this target exactly, or None
        (:func:`impactmaps.targets.map_structure.describing_structure`)."""
        return describing_structure(self, patch_loaded)[0]

    def map_structure_refusal(self, *, patch_loaded: bool = False) -> str | None:
        """Why no reference structure describes this target, or None."""
        return describing_structure(self, patch_loaded)[1]

    def similarity_groups(self) -> dict:
        """The dimensionless groups fixing the target's normalised response."""
        return similarity_groups(self)

    @classmethod
    def infinite_structure_peak(cls, loss_factor):
        """Normalised peak force F̄∞(ζ) [-] on the infinite structure; ``loss_factor`` ζ [-] may be an array."""
        raise NotImplementedError(f"{cls.__name__} has no infinite-structure asymptote")

    @classmethod
    def infinite_structure_impact(cls, loss_factor: float) -> InfiniteImpact:
        """The whole infinite-structure impact at one loss factor ζ [-] (:class:`InfiniteImpact`)."""
        raise NotImplementedError(f"{cls.__name__} has no infinite-structure asymptote")
