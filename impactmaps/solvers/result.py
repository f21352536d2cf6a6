"""The result of one impact simulation: labelled histories plus scalars."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import pandas as pd

__all__ = ["ImpactResult", "ContactIntervals"]


class ContactIntervals:
    """Derived contact scalars of any result with a ``contact_intervals`` (k, 2) array [s]."""

    contact_intervals: np.ndarray

    @property
    def impacts(self) -> int:
        """Number of separate contacts (impacts)."""
        return int(len(self.contact_intervals))

    @property
    def contact_durations(self) -> np.ndarray:
        """Duration of each contact [s]."""
        return np.diff(self.contact_intervals, axis=1).ravel()

    @property
    def contact_time(self) -> float:
        """Total time in contact, summed over all impacts [s]."""
        return float(np.nansum(self.contact_durations))

    @property
    def first_contact_duration(self) -> float:
        """Duration of the first contact [s]."""
        return float(self.contact_durations[0]) if self.impacts else 0.0


@dataclass(frozen=True)
class ImpactResult(ContactIntervals):
    """Outcome of one sphere impact on a target (SI units).

    Attributes
    ----------
    history : pandas.DataFrame or None
        Time histories, one row per step: ``time_s, force_N, indentation_m,
        impactor_displacement_m, impactor_velocity_m_s, target_displacement_m,
        target_velocity_m_s, structure_energy_J, impactor_kinetic_energy_J``
        (displacements positive into the target; the energy the contact holds or has
        dissipated is the impact energy minus the two energies). ``None`` when the run kept scalars only.
    peak_force : float
        Largest contact force over the whole event, all impacts [N].
    peak_time : float
        Time of the peak force [s].
    contact_intervals : ndarray, shape (k, 2)
        Start and end time of each contact [s]; ``k`` is the number of impacts.
    max_indentation : float
        Largest indentation reached [m].
    permanent_indentation : float
        Permanent indentation left by the contact law [m] (0 for elastic laws).
    rebound_velocity : float
        Impactor velocity away from the target at the end of the run [m/s].
    energy_transferred : float
        Vibration energy left in the structure at the end [J].
    contact_dissipation : float
        Energy dissipated in the contact zone [J].
    damping_work : float
        Energy dissipated by modal damping [J].
    impact_energy : float
        Impactor kinetic energy before impact ½ m V0² [J].
    end_time : float
        Time at which the run stopped [s] (re-impact impossible, or the limit).
    hit_time_limit : bool
        True if the run stopped at its time limit rather than because re-impact had
        become impossible; the scalars then describe a truncated event.
    impactor_mass, velocity, contact_frequency : float
        m_i [kg], V0 [m/s], and the contact frequency ω [rad/s] used to normalise
        (``sqrt(K/m_i)`` for a linear law; the tangent-stiffness value at the
        half-space peak indentation for a nonlinear law).
    n_modes : int
        Number of modes integrated (0 for a half-space).
    time_step : float
        Integration time step [s].
    method : str
        Which model produced the result (e.g. ``"modal"``, ``"modal+residual"``).
    settings : dict
        Solver settings used (for provenance).
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
    impact_energy: float
    end_time: float
    hit_time_limit: bool
    impactor_mass: float
    velocity: float
    contact_frequency: float
    n_modes: int
    time_step: float
    method: str
    settings: dict = field(default_factory=dict)

    # -- derived scalars ------------------------------------------------------------
    @property
    def restitution(self) -> float:
        """Impactor rebound speed over approach speed [-]."""
        return self.rebound_velocity / self.velocity

    @property
    def energy_balance_error(self) -> float:
        """|E_in − (E_rebound + E_structure + E_contact + E_damping)| / E_in [-]."""
        out = (
            0.5 * self.impactor_mass * self.rebound_velocity**2
            + self.energy_transferred
            + self.contact_dissipation
            + self.damping_work
        )
        return abs(self.impact_energy - out) / self.impact_energy

    # -- normalised view (seed 001 eqs 20, 26) ---------------------------------------
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
        return self.contact_time * self.contact_frequency

    @property
    def first_contact_duration_normalised(self) -> float:
        """First contact duration in units of 1/ω [-]."""
        return self.first_contact_duration * self.contact_frequency

    @property
    def peak_time_normalised(self) -> float:
        """Time of the peak in units of 1/ω [-]."""
        return self.peak_time * self.contact_frequency

    @property
    def energy_transferred_fraction(self) -> float:
        """Fraction of the impact energy left in the structure [-]."""
        return self.energy_transferred / self.impact_energy

    def normalised_history(self) -> pd.DataFrame:
        """Histories in the normalised variables τ = ωt, F̄ = F/(m_iV0ω), x̄ = x/α*."""
        if self.history is None:
            raise ValueError("this result kept no history (run with record=True)")
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
            "hit_time_limit": int(self.hit_time_limit),
        }

    def summary(self) -> dict:
        """The scalars as a flat dict with unit-suffixed keys (JSON-ready)."""
        return {
            "peak_force_N": float(self.peak_force),
            "peak_time_s": float(self.peak_time),
            "impacts": self.impacts,
            "contact_intervals_s": self.contact_intervals.tolist(),
            "contact_time_s": self.contact_time,
            "max_indentation_m": float(self.max_indentation),
            "permanent_indentation_m": float(self.permanent_indentation),
            "rebound_velocity_m_s": float(self.rebound_velocity),
            "restitution": float(self.restitution),
            "energy_transferred_J": float(self.energy_transferred),
            "contact_dissipation_J": float(self.contact_dissipation),
            "damping_work_J": float(self.damping_work),
            "impact_energy_J": float(self.impact_energy),
            "energy_balance_error": float(self.energy_balance_error),
            "fmax_normalised": float(self.fmax_normalised),
            "contact_time_normalised": float(self.contact_time_normalised),
            "hit_time_limit": bool(self.hit_time_limit),
            "n_modes": int(self.n_modes),
            "method": self.method,
        }
