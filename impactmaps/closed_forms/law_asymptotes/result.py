"""The result shape every any-law asymptote returns (SI units, JSON-ready summary)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...contact.contact_scale import reference_contact_stiffness

__all__ = ["AsymptoteResult", "contact_frequency_of"]


def contact_frequency_of(law, impactor_mass: float, velocity: float) -> float:
    """Contact frequency ω = sqrt(K_ref/m) [rad/s] used to normalise (K_ref:
    :func:`impactmaps.contact.contact_scale.reference_contact_stiffness`)."""
    return math.sqrt(reference_contact_stiffness(law, impactor_mass, velocity) / impactor_mass)


@dataclass(frozen=True)
class AsymptoteResult:
    """Outcome of one impact on an asymptotic structure, for any contact law.

    Attributes
    ----------
    method : str
        ``"infinite-plate"``, ``"infinite-beam"``, ``"quasi-static"`` or ``"half-space"``.
    peak_force, peak_time : float
        Largest contact force [N] and its time [s].
    contact_time : float
        First touch to last separation [s]; ``inf`` when the run ended in contact.
    restitution : float
        Rebound over approach speed after the last separation [-]; 0 at rest in contact.
    fmax_normalised : float
        ``peak_force / (m V0 ω)`` [-].
    impacts : int
        Number of separate contacts.
    contact_intervals : tuple of (float, float)
        Start and end of each contact [s] (end ``inf`` if still in contact).
    max_indentation, permanent_indentation : float
        α_max and the permanent indentation after unloading from it [m].
    max_target_displacement : float
        Largest displacement of the struck point [m].
    impactor_mass, velocity, contact_frequency : float
        m [kg], V0 [m/s], ω [rad/s].
    time_limit_reached : bool
        True when the run stopped at its time limit with the event not provably over.
    """

    method: str
    peak_force: float
    peak_time: float
    contact_time: float
    restitution: float
    fmax_normalised: float
    impacts: int
    contact_intervals: tuple
    max_indentation: float
    permanent_indentation: float
    max_target_displacement: float
    impactor_mass: float
    velocity: float
    contact_frequency: float
    time_limit_reached: bool = False

    def summary(self) -> dict:
        """The scalars as a flat dict with unit-suffixed keys (``inf``/``nan`` kept as floats)."""
        return {
            "method": self.method,
            "peak_force_N": float(self.peak_force),
            "contact_time_s": float(self.contact_time),
            "restitution": float(self.restitution),
            "fmax_normalised": float(self.fmax_normalised),
            "impacts": int(self.impacts),
            "peak_time_s": float(self.peak_time),
            "contact_intervals_s": [list(map(float, pair)) for pair in self.contact_intervals],
            "max_indentation_m": float(self.max_indentation),
            "permanent_indentation_m": float(self.permanent_indentation),
            "max_target_displacement_m": float(self.max_target_displacement),
            "time_limit_reached": bool(self.time_limit_reached),
        }

    @property
    def contact_time_normalised(self) -> float:
        """``contact_time · ω`` [-]."""
        return self.contact_time * self.contact_frequency


def contact_intervals_from_samples(time, force, clearance=None) -> tuple:
    """Contact intervals ((start, end), …) [s] from sampled forces (end ``inf`` if open),
    interpolated at zero crossings of ``clearance`` [m] when given."""
    time = np.asarray(time, dtype=float)
    touching = np.asarray(force) > 0.0
    edges = np.flatnonzero(np.diff(touching.astype(int)))

    def crossing(i):
        if clearance is None:
            return float(time[i + 1])
        low, high = clearance[i], clearance[i + 1]
        if low == high:
            return float(time[i + 1])
        share = min(max(low / (low - high), 0.0), 1.0)
        return float(time[i] + share * (time[i + 1] - time[i]))

    starts = [crossing(i) for i in edges if not touching[i]]
    if touching.size and touching[0]:
        starts.insert(0, float(time[0]))
    ends = [crossing(i) for i in edges if touching[i]]
    if len(ends) < len(starts):
        ends.append(math.inf)
    return tuple(zip(starts, ends))
