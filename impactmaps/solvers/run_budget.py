"""Budgets before work: what a run will hold and how long it will take, checked before it starts.

A run estimated above :data:`MEMORY_LIMIT_BYTES` is refused (``ValueError`` naming the
knob and the value that fits); one above :data:`LONG_RUN_SECONDS` is announced
(:class:`LongRunWarning`). :func:`modal_run_budget` estimates a modal run.
"""

from __future__ import annotations

import math
import warnings
from typing import NamedTuple

__all__ = ["MEMORY_LIMIT_BYTES", "LONG_RUN_SECONDS", "HISTORY_ROW_BYTES", "HISTORY_ROW_CAP", "INTERVAL_BYTES",
           "BYTES_PER_MODE",
           "SECONDS_PER_MODE_STEP", "EXPECTED_RUN_RATIO", "MAX_STEPS", "LongRunWarning", "RunBudget",
           "refuse_or_announce", "modal_run_budget", "SECONDS_PER_MAP_POINT", "SECONDS_PER_RITZ_MAP_POINT",
           "RITZ_BASIS_SECONDS", "map_sweep_seconds"]

#: Memory one run may take [B].
MEMORY_LIMIT_BYTES = 1 << 30
#: Runs estimated to take longer than this [s] are announced before they start.
LONG_RUN_SECONDS = 60.0
#: Bytes per recorded history row of a modal run: 8 float64 in the kernel's array, which
#: grows by doubling (up to 2×), its trimmed copy (1×) and the DataFrame with the impactor's
#: kinetic energy (9 columns): (16 + 8 + 9) × 8 = 264 B, rounded up.
HISTORY_ROW_BYTES = 320
#: Most history rows a recorded modal run writes (≈ 0.3 GiB at :data:`HISTORY_ROW_BYTES`):
#: the integrator stops a run there (``row_cap_reached``) instead of growing its history.
#: Not a :class:`~impactmaps.solvers.modal_settings.ModalSettings` field: the settings are part of
#: every sweep's fingerprint, so a new field would orphan the shipped results.
HISTORY_ROW_CAP = 1_000_000
#: Bytes per entry of the contact-interval table (start and end, float64), allocated whole.
INTERVAL_BYTES = 16
#: Bytes per integrated mode (the integrator's 70 float64 per mode and the basis), as the
#: mode budget counts them (:data:`impactmaps.solvers.mode_budget.BYTES_PER_MODE`).
BYTES_PER_MODE = 1024
#: Seconds per mode and step of the compiled integrator, rounded up from 9–48 ns measured on
#: the 2-core reference machine (SSSS Kirchhoff plate, 72–5810 modes, 261–2049 steps,
#: sampled contact phase).
SECONDS_PER_MODE_STEP = 5e-8
#: Expected length of a modal run in units of 1/ω for the time estimate (measured end times
#: 4 … 13 /ω on plates from ζ = 0.03 to 1; a run with many re-impacts lasts longer).
EXPECTED_RUN_RATIO = 20.0
#: Most expected steps a forced time step may give.
MAX_STEPS = 10**8


class LongRunWarning(UserWarning):
    """A run is estimated to take longer than :data:`LONG_RUN_SECONDS` (said before it starts;
    the command line prints it at once, the other warnings after the output)."""

    announce_at_once = True


class RunBudget(NamedTuple):
    """The estimate of one run: ``memory_bytes`` [B], ``seconds`` [s], ``advice`` (the knob and
    the value that fits, for a refusal) and ``hint`` (what makes it faster, may be empty).
    """

    memory_bytes: float
    seconds: float
    advice: str
    hint: str = ""


def refuse_or_announce(budget: RunBudget, what: str, stacklevel: int = 3) -> None:
    """Refuse (``ValueError``) a run above :data:`MEMORY_LIMIT_BYTES`, announce
    (:class:`LongRunWarning`, at ``stacklevel``) one above :data:`LONG_RUN_SECONDS`;
    ``what`` names the run in the messages.
    """
    if budget.memory_bytes > MEMORY_LIMIT_BYTES:
        raise ValueError(f"{what} may take {budget.memory_bytes / 2**30:.3g} GiB (limit "
                         f"{MEMORY_LIMIT_BYTES / 2**30:g} GiB): {budget.advice}")
    if budget.seconds > LONG_RUN_SECONDS:
        hint = f" ({budget.hint})" if budget.hint else ""
        warnings.warn(f"{what}: about {budget.seconds:.0f} s on a 2-core machine{hint}", LongRunWarning,
                      stacklevel=stacklevel)


def modal_run_budget(n_modes: int, time_step: float, max_time: float, contact_frequency: float, record: bool,
                     max_events: int, forced_step: bool) -> RunBudget:
    """The :class:`RunBudget` of one run of the modal integrator: ``n_modes`` modes, step
    ``time_step`` and limit ``max_time`` [s], contact frequency ω [rad/s], ``record`` (history
    kept), ``max_events`` (interval-table capacity), ``forced_step`` (the user gave the step).

    Raises
    ------
    ValueError
        A forced step with more than :data:`MAX_STEPS` expected steps, naming
        ``time_step`` and the value that fits.
    """
    steps = math.ceil(max_time / time_step) + 2
    expected = min(steps, math.ceil(EXPECTED_RUN_RATIO / (contact_frequency * time_step)) + 2)
    room = MEMORY_LIMIT_BYTES - n_modes * BYTES_PER_MODE
    if max_events * INTERVAL_BYTES > room / 2:
        return RunBudget(float(MEMORY_LIMIT_BYTES + 1), 0.0, (
            f"max_events = {max_events} holds {max_events * INTERVAL_BYTES / 2**30:.3g} GiB of contact "
            f"intervals; valid range: max_events ≤ {int(room / 2 // INTERVAL_BYTES)}"))
    fits = MAX_STEPS  # the most expected steps that fit (memory of the history, and MAX_STEPS)
    if record:
        fits = min(fits, int((room - max_events * INTERVAL_BYTES) // HISTORY_ROW_BYTES))
    # the step at which the expected steps fit (the time limit, if it binds, scales the same way)
    step_that_fits = time_step * (expected - 2) / max(fits - 2, 1)
    if forced_step and expected > MAX_STEPS:
        raise ValueError(f"time_step = {time_step:.6g} s is invalid: {expected:.3g} steps expected (at most "
                         f"{MAX_STEPS:.0e}); valid range: time_step ≥ {step_that_fits:.3g} s")
    rows = min(expected, HISTORY_ROW_CAP) if record else 0
    memory = max_events * INTERVAL_BYTES + n_modes * BYTES_PER_MODE + rows * HISTORY_ROW_BYTES
    seconds = expected * max(n_modes, 1) * SECONDS_PER_MODE_STEP
    hint = "a smaller cutoff_ratio, a shorter time limit or fewer modes are faster"
    if memory <= MEMORY_LIMIT_BYTES:  # the advice is read by a refusal only: not formatted for every run
        return RunBudget(float(memory), float(seconds), "", hint)
    if forced_step:
        knob = f"time_step ≥ {step_that_fits:.3g} s"
    elif expected == steps:  # the time limit binds
        ratio = max_time * contact_frequency
        knob = (f"max_time_ratio ≤ {ratio * (fits - 2) / steps:.3g} (solver.duration ≤ "
                f"{max_time * (fits - 2) / steps:.3g} s)")
    else:
        knob = "a lighter or heavier impactor (the step follows the modes the contact excites)"
    advice = (f"the history is expected to hold {rows:.3g} rows (one per step of {time_step:.3g} s over "
              f"{rows * time_step:.3g} s, time limit {max_time:.3g} s); use {knob}, or run without the "
              "history (record=False)")
    return RunBudget(float(memory), float(seconds), advice, hint)


# -- map sweeps ---------------------------------------------------------------------------------
# CPU of the linear law's map points by the modal basis of the structure, said before a sweep
# starts (impactmaps.maps.compute.sweep): a point of a beam or a Navier plate (SSSS, specially
# orthotropic) is cheap; a plate of the Ritz basis (a clamped or free edge, D16/D26) first builds
# its basis (a dense eigenproblem, kept on disk afterwards: impactmaps.targets.plates.basis_cache),
# then integrates more modes a point. Hertz and elastic-plastic points cost more. For planning,
# not a bound: the basis is counted as not yet cached.

#: CPU of a map point on a beam or a Navier plate [s]: the mean of the linear plane (200 × 50,
#: beam and plate: 58 CPU-s for 20 000 points, ``benchmarks/studies/RESULTS_plane.md``).
SECONDS_PER_MAP_POINT = 2.9e-3
#: CPU of a map point on a plate of the Ritz basis, its basis built [s]: the largest mean measured
#: on 20 ζ from 0.005 to 100 × λ = 0.05, 0.2, 1, 5 (one process, 2 cores at load 7–8): CCCC
#: Kirchhoff 0.14–0.20, CFCF Kirchhoff (b/a 0.667) 0.07, CCCC Mindlin (a/h 20) and the CCCC
#: Mindlin [45/0/−45/90]2s laminate of the drop-weight example 0.002–0.003 (their points stop
#: where the basis resolves no more); a beam or a Navier plate 0.01 on that grid.
SECONDS_PER_RITZ_MAP_POINT = 0.2
#: CPU of building a Ritz basis, once per structure while it is not cached [s]: the largest basis
#: (the map's cap, :func:`impactmaps.solvers.mode_budget.frequency_cap`) of the drop-weight laminate
#: took 1.4 s, of a 150 × 100 × 3 mm CCCC Mindlin plate 1.6 s (2026-12-03, the block Krylov
#: eigen-solution and rectangular bases; about 33 and 16 s before); rounded up for the static factors
#: the points add.
RITZ_BASIS_SECONDS = 5.0


def map_sweep_seconds(points, ritz) -> float:
    """The CPU of a map sweep [s] computing ``points[k]`` points of the k-th structure, a plate of
    the Ritz basis where ``ritz[k]`` (then with its basis's build, :data:`RITZ_BASIS_SECONDS`)."""
    return float(sum(count * SECONDS_PER_RITZ_MAP_POINT + RITZ_BASIS_SECONDS if on_ritz
                     else count * SECONDS_PER_MAP_POINT for count, on_ritz in zip(points, ritz) if count))
