"""The result of one impact, whichever solver produced it: labelled histories plus scalars.

Every solver returns :class:`ImpactResult`; what only one solver knows travels in
``details``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["ImpactResult", "HISTORY_COLUMNS", "energy_balance_error"]

#: History columns every solver writes (SI units, displacements positive into the
#: target). Solvers may add their own after these (the modal solver's energies, the
#: finite-difference beam's gauges).
HISTORY_COLUMNS = (
    "time_s",
    "force_N",
    "indentation_m",
    "impactor_displacement_m",
    "impactor_velocity_m_s",
    "target_displacement_m",
    "target_velocity_m_s",
)


def energy_balance_error(impactor_mass, velocity, rebound_velocity, *sinks) -> float:
    """|E_in − (E_rebound + Σ sinks)| / E_in [-] of one impact of ``impactor_mass`` m_i [kg] at
    ``velocity`` V0 [m/s] rebounding at ``rebound_velocity`` [m/s]; ``sinks``: the other
    energies at the end [J].
    """
    impact = 0.5 * impactor_mass * velocity**2
    out = 0.5 * impactor_mass * rebound_velocity**2 + sum(sinks)
    return abs(impact - out) / impact


def _total_duration(durations: np.ndarray) -> float:
    """``np.nansum(durations)`` [s]: the same sum (NumPy's pairwise ``add.reduce``), skipping
    the NaN-replacing copy when no duration is NaN (a NaN makes the plain sum NaN)."""
    total = float(durations.sum())
    return total if total == total else float(np.nansum(durations))



@dataclass(frozen=True)
class ImpactResult:
    """Outcome of one sphere impact (SI units).

    Attributes
    ----------
    history : pandas.DataFrame or None
        Time histories, one row per recorded step: :data:`HISTORY_COLUMNS` (SI units in
        the names; the target's displacement is the struck point's) and solver extras.
        ``None`` when the run kept scalars only.
    peak_force, peak_time : float
        Largest contact force over the whole event [N] and its time [s].
    contact_intervals : ndarray, shape (k, 2)
        Start and end time of each contact [s]; ``k`` is the number of impacts.
    max_indentation, permanent_indentation : float
        α_max and the permanent indentation after unloading from it [m].
    rebound_velocity : float
        Impactor velocity away from the target after its last separation [m/s];
        ``nan`` when the run ended before the sphere separated (a warning says so).
    energy_transferred, contact_dissipation, damping_work : float
        Vibration energy left in the structure, energy dissipated in the contact
        (``law.dissipated_energy(α_max)``) and by structural damping [J].
    energy_balance_error : float
        Residual of the energy ledger relative to the impact energy [-].
    impactor_mass, velocity : float
        m_i [kg] and V0 [m/s].
    contact_frequency : float
        ω [rad/s] used to normalise: ``sqrt(K/m_i)`` for a linear law, the loading
        tangent at the half-space peak indentation for a nonlinear law.
    end_time, time_step : float
        Time the run stopped [s]; integration (or sampling) time step [s].
    time_limit_reached : bool
        The run stopped at its time limit while the event could still go on.
    method : str
        The model that produced the result: ``"modal"``, ``"modal+residual"``,
        ``"half-space"`` or ``"finite-difference"``.
    n_modes : int
        Number of modes integrated, as the impact point sees them (degenerate ones once;
        0 for the half-space and finite-difference solvers).
    settings : dict
        Solver settings used (provenance).
    details : object or None
        Solver-specific extras (:class:`impactmaps.fd.FDDetails`,
        :class:`impactmaps.solvers.modal_settings.ModalDetails`) or ``None``.
    converged, convergence_note : bool or None, str
        Whether F̄max held when the cut-off was doubled and the step halved (``None``:
        not checked), and why not.
    """

    history: pd.DataFrame | None
    peak_force: float
    peak_time: float
    contact_intervals: np.ndarray
    max_indentation: float
    permanent_indentation: float
    rebound_velocity: float
    energy_transferred: float
    contact_dissipation: float
    damping_work: float
    energy_balance_error: float
    impactor_mass: float
    velocity: float
    contact_frequency: float
    end_time: float
    time_limit_reached: bool
    time_step: float
    method: str
    n_modes: int = 0
    settings: dict = field(default_factory=dict)
    details: Any = None
    converged: bool | None = None
    convergence_note: str = ""

    @classmethod
    def from_fields(cls, fields: dict) -> "ImpactResult":
        """The result ``cls(**fields)`` builds, field for field, for a solver's hot path (``fields``:
        every field by name; other names go through the constructor).
        """
        if fields.keys() != _FIELD_NAMES:
            return cls(**fields)
        result = object.__new__(cls)
        result.__dict__.update(fields)
        return result

    # -- contacts -----------------------------------------------------------------------
    @property
    def impacts(self) -> int:
        """Number of separate contacts (impacts)."""
        return int(len(self.contact_intervals))

    @property
    def contact_durations(self) -> np.ndarray:
        """Duration of each contact [s] (``nan`` for a contact still open at the end)."""
        intervals = self.contact_intervals
        if type(intervals) is np.ndarray and intervals.ndim == 2 and intervals.shape[1] == 2:  # noqa: E721
            return intervals[:, 1] - intervals[:, 0]  # np.diff's subtraction, without its ~5 µs of Python
        return np.diff(intervals, axis=1).ravel()

    @property
    def total_contact_time(self) -> float:
        """Total time in contact, summed over all impacts [s]."""
        return _total_duration(self.contact_durations)

    @property
    def first_contact_duration(self) -> float:
        """Duration of the first contact [s] (0 when the sphere never touched)."""
        return float(self.contact_durations[0]) if self.impacts else 0.0

    @property
    def contact_span(self) -> float:
        """From the first contact's start to the last contact's end [s]."""
        if not self.impacts:
            return 0.0
        return float(self.contact_intervals[-1, 1] - self.contact_intervals[0, 0])

    # -- energies -------------------------------------------------------------------------
    @property
    def impact_energy(self) -> float:
        """Impactor kinetic energy before impact ½ m_i V0² [J]."""
        return 0.5 * self.impactor_mass * self.velocity**2

    @property
    def restitution(self) -> float:
        """Impactor rebound speed over approach speed [-] (``nan`` if not separated)."""
        return self.rebound_velocity / self.velocity

    @property
    def energy_loss(self) -> float:
        """Kinetic energy the impactor lost, ½ m_i (V0² − V_r²) [J] (``nan`` if not separated)."""
        return self.impact_energy - 0.5 * self.impactor_mass * self.rebound_velocity**2

    @property
    def energy_transferred_fraction(self) -> float:
        """Fraction of the impact energy left in the structure [-]."""
        return self.energy_transferred / self.impact_energy

    # -- normalised view (seed 001 eqs 20, 26) ---------------------------------------------
    @property
    def force_scale(self) -> float:
        """m_i V0 ω [N], the half-space peak force of the linear law."""
        return self.impactor_mass * self.velocity * self.contact_frequency

    @property
    def fmax_normalised(self) -> float:
        """Normalised peak force F̄max = F_max/(m_i V0 ω) [-]."""
        return self.peak_force / self.force_scale

    @property
    def contact_time_normalised(self) -> float:
        """Total contact time in units of 1/ω [-]."""
        return self.total_contact_time * self.contact_frequency

    @property
    def first_contact_duration_normalised(self) -> float:
        """First contact duration in units of 1/ω [-]."""
        return self.first_contact_duration * self.contact_frequency

    @property
    def peak_time_normalised(self) -> float:
        """Time of the peak in units of 1/ω [-]."""
        return self.peak_time * self.contact_frequency

    def normalised_history(self) -> pd.DataFrame:
        """Histories in the normalised variables τ = ωt, F̄ = F/(m_iV0ω), x̄ = x/α*."""
        if self.history is None:
            raise ValueError("this result kept no history (run with record=True)")
        import pandas as pd  # a history is a DataFrame: pandas is loaded with the first one

        alpha_star = self.velocity / self.contact_frequency
        h = self.history
        return pd.DataFrame(
            {
                "tau": h["time_s"] * self.contact_frequency,
                "force_normalised": h["force_N"] / self.force_scale,
                "indentation_normalised": h["indentation_m"] / alpha_star,
                "impactor_displacement_normalised": h["impactor_displacement_m"] / alpha_star,
                "target_displacement_normalised": h["target_displacement_m"] / alpha_star,
            }
        )

    def normalised_summary(self) -> dict:
        """The normalised scalars of the ζ–λ maps (keys as in the map datasets)."""
        return {
            "fmax_normalised": self.fmax_normalised,
            "impacts": self.impacts,
            "contact_time_normalised": self.contact_time_normalised,
            "first_contact_normalised": self.first_contact_duration_normalised,
            "peak_time_normalised": self.peak_time_normalised,
            "energy_transferred_fraction": self.energy_transferred_fraction,
            "n_modes": self.n_modes,
            "time_limit_reached": int(self.time_limit_reached),
        }

    def summary(self) -> dict:
        """The scalars as a flat dict with unit-suffixed keys (JSON-ready).

        Quantities that do not exist for this run are ``nan`` (the writers write ``null``).
        """
        out = {
            "peak_force_N": float(self.peak_force),
            "peak_time_s": float(self.peak_time),
            "impacts": self.impacts,
            "contact_intervals_s": self.contact_intervals.tolist(),
            "first_contact_duration_s": self.first_contact_duration,
            "total_contact_time_s": self.total_contact_time,
            "max_indentation_m": float(self.max_indentation),
            "permanent_indentation_m": float(self.permanent_indentation),
            "rebound_velocity_m_s": float(self.rebound_velocity),
            "restitution": float(self.restitution),
            "impact_energy_J": float(self.impact_energy),
            "energy_loss_J": float(self.energy_loss),
            "energy_transferred_J": float(self.energy_transferred),
            "contact_dissipation_J": float(self.contact_dissipation),
            "damping_work_J": float(self.damping_work),
            "energy_balance_error": float(self.energy_balance_error),
            "fmax_normalised": float(self.fmax_normalised),
            "contact_time_normalised": float(self.contact_time_normalised),
            "time_limit_reached": bool(self.time_limit_reached),
            "time_step_s": float(self.time_step),
            "n_modes": int(self.n_modes),
            "method": self.method,
            "converged": self.converged,
        }
        if self.convergence_note:
            out["converged_note"] = self.convergence_note
        if self.details is not None:
            out.update(self.details.summary())
        return out


#: The field names of :class:`ImpactResult` (what :meth:`ImpactResult.from_fields` takes).
_FIELD_NAMES = frozenset(f.name for f in fields(ImpactResult))
