"""Every map point with its error: refinement, an error estimate and a status.

A point of a map is solved at the sweep's settings and again with the mode cut-off
doubled and the time step really halved (:meth:`ModalSettings.refined
<impactmaps.solvers.modal_settings.ModalSettings.refined>`). The difference is the point's error
estimate. When it exceeds the tolerance the point is refined again, within a cost cap;
a point that still does not settle has no converged value, and the map says so with the
spread of F̄max over small perturbations of cut-off, step and ζ instead of one number.

Statuses (the ``status`` variable of a map; ``STATUSES[code]``):

``converged``
    The first refinement moved F̄max by at most the tolerance and kept the number of
    impacts; the stored value is the refined one and ``fmax_error`` is that move (stored
    as measured; what a user is told is at least its floor, :func:`stated_error`: 2e-4,
    1e-3 with re-impacts).
``refined``
    It took more refinements (cut-off ×2ᵏ, step /2ᵏ) to settle; the stored value is the
    finest and ``fmax_error`` the last move (stated with its floor, as ``converged``).
``sensitive``
    No converged value within the cost cap (many re-impacts whose order flips with any
    change of the model): ``fmax_low``/``fmax_high`` bound every value seen (every
    refinement level and the runs perturbed from the base settings) and the finest value
    ± its last change (at least the tolerance); the stored value is the finest,
    ``fmax_error`` half the spread.
``asymptotic``
    Answered by an exact asymptote (the ``method`` variable says which); error 0.
``unresolved``
    No value the toolkit vouches for, and none stored (every result variable missing):
    the contact frequency lies beyond what the target's Timoshenko/Mindlin theory holds
    (:mod:`impactmaps.targets.shear_range`), or the point needs more modes than the cap
    and no exact asymptote answers it. Lookups refuse there.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from enum import StrEnum
from typing import Callable

import numpy as np

from ..._checks import require_in_range, require_positive

__all__ = ["STATUSES", "PointStatus", "AccuracyControl", "ERROR_FLOOR", "REIMPACT_ERROR_FLOOR",
           "TILE_REIMPACT_RELATIVE_FLOOR", "stated_error", "stated_row",
           "controlled_point", "exact_point", "perturbed_runs", "settled", "SEVERITY", "BAND_TOLERANCE", "answer_status",
           "corner_status", "status_notes"]


class PointStatus(StrEnum):
    """The status of a map point (module docstring); its code is its index in :data:`STATUSES`."""

    CONVERGED = "converged"
    REFINED = "refined"
    SENSITIVE = "sensitive"
    ASYMPTOTIC = "asymptotic"
    UNRESOLVED = "unresolved"


#: Status names by code (the ``status`` variable; CF flag_values/flag_meanings).
STATUSES = tuple(status.value for status in PointStatus)


@dataclass(frozen=True)
class AccuracyControl:
    """How hard a sweep works for each point's accuracy.

    Attributes
    ----------
    tolerance : float
        Largest accepted change of F̄max between two refinement levels [-].
    max_refinements : int
        Cost cap: refinement levels beyond the base run (level k costs about 4ᵏ base
        runs: 2ᵏ the modes, 1/2ᵏ the step). 1 gives the plain check.
    perturbation : float
        Relative size of the perturbations of cut-off, step and ζ that measure the
        spread of a sensitive point [-].
    """

    tolerance: float = 1e-3
    max_refinements: int = 2
    perturbation: float = 0.01

    def __post_init__(self):
        require_positive("tolerance", self.tolerance)
        require_in_range("max_refinements", self.max_refinements, 1, 6)
        if int(self.max_refinements) != self.max_refinements:
            raise ValueError(f"max_refinements = {self.max_refinements!r} is invalid: must be an integer")
        require_in_range("perturbation", self.perturbation, 0.0, 0.2, low_inclusive=False)


#: Least ``fmax_error`` of a ``converged`` or ``refined`` point of one impact [-]. The change
#: between a point's last two levels misses the finest level's own error where that change is
#: accidentally small (the levels integrate their contacts alike, or two error terms cancel):
#: the change alone covered the error against a reference four levels above the base at 69 %
#: of 1024 random converged points of the four shipped families (74 % in issue 40's audit),
#: the floors at ≥ 99 % of each family's (``validation/band_audit.md``, docs/accuracy.rst;
#: calibrated on another seed). Single impacts erred by ≤ 8.7e-5 there (≤ 1.7e-4 in the calibration).
ERROR_FLOOR = 2e-4
#: The same for a point with re-impacts [-]: a re-impact's timing moves its peak by more
#: than the levels' change shows, up to ~1e-3 where the finer levels change the sequence.
REIMPACT_ERROR_FLOOR = 1e-3
#: The re-impact floor of a point of an on-demand refined-cell tile (a plate of a Ritz basis:
#: clamped or free edges, laminates), relative to the point's own F̄max [-], between
#: :data:`ERROR_FLOOR` and :data:`REIMPACT_ERROR_FLOOR` (:func:`stated_error` with ``fmax``).
#: The absolute 1e-3 is ~4 % of the F̄max ≈ 0.025 of a heavy impactor on a laminate
#: (ζ_h ≈ 100), where the converged or refined points of 11 refined-cell laminate tiles (73 of
#: their 99 points) erred by ≤ 0.38 % of F̄max with re-impacts (≤ 0.17 % without) against
#: references four refinement levels above the base run, each within 0.53 of its stated error
#: with this floor (``validation/laminate_tile_bands.py --points``, ``laminate_tile_bands.md``;
#: docs/lookup.rst). (A Navier 4 × 4 laminate tile's point whose impact sequence changed erred
#: by 1.2 %, within its measured change, 1.6 %: its patch cut-off stopped at 80 ω below the
#: heavy-impactor corner's; every laminate now has a refined cell whose points use that corner,
#: and the isotropic SSSS plates' 4 × 4 tiles keep the absolute floors.)
TILE_REIMPACT_RELATIVE_FLOOR = 1e-2


def stated_error(error, status, impacts=None, fmax=None):
    """A point's stated ``fmax_error`` from the change its refinement measured [-].

    Where the point is ``converged`` or ``refined`` (status codes of :data:`STATUSES`), at
    least :data:`ERROR_FLOOR`, or :data:`REIMPACT_ERROR_FLOOR` where it has more than one
    impact (``impacts``; not given: one); elsewhere the error as given. With ``fmax`` (the
    points' F̄max, a refined-cell tile's: :func:`impactmaps.maps.compute.tiles.tile_refinement`)
    the re-impact floor is :data:`TILE_REIMPACT_RELATIVE_FLOOR` · F̄max, clipped to
    [:data:`ERROR_FLOOR`, :data:`REIMPACT_ERROR_FLOOR`]. Arrays or scalars; idempotent.

    Maps, sweeps and shipped results store the change as measured (:func:`controlled_point`),
    so a stored point is the same bits however it was computed; the floor is applied where an
    error is stated to a user: when a map is read (a lookup's band) and by :func:`stated_row`
    (the ``point`` command).
    """
    given, status = np.asarray(error), np.asarray(status)
    reimpact = REIMPACT_ERROR_FLOOR if fmax is None else np.clip(
        TILE_REIMPACT_RELATIVE_FLOOR * np.abs(np.nan_to_num(np.asarray(fmax, float), nan=1.0)), ERROR_FLOOR,
        REIMPACT_ERROR_FLOOR)
    floor = np.where(np.asarray(impacts if impacts is not None else 1) > 1, reimpact, ERROR_FLOOR)
    settled_point = (status == STATUSES.index("converged")) | (status == STATUSES.index("refined"))
    out = np.where(settled_point & np.isfinite(given), np.maximum(given, floor), given).astype(given.dtype)
    return out.item() if out.ndim == 0 else out


def stated_row(row: dict) -> dict:
    """A map point's row (:func:`controlled_point`) as a user is told it: ``fmax_error`` with
    its floor (:func:`stated_error`) and, where the floor widened it, ``fmax_low``/``fmax_high``
    F̄max ∓ that error."""
    error = stated_error(row["fmax_error"], row["status"], row.get("impacts"))
    if not error > row["fmax_error"]:
        return dict(row)
    fmax = row["fmax_normalised"]
    return row | {"fmax_error": error, "fmax_low": fmax - error, "fmax_high": fmax + error}


def _row(result, status: str, error: float, low: float, high: float) -> dict:
    return result.normalised_summary() | {
        "fmax_error": float(error),
        "fmax_low": float(low),
        "fmax_high": float(high),
        "status": STATUSES.index(status),
    }


def exact_point(row: dict) -> dict:
    """The error columns of a point answered exactly (an asymptote): error 0."""
    value = float(row["fmax_normalised"])
    return row | {"fmax_error": 0.0, "fmax_low": value, "fmax_high": value,
                  "status": STATUSES.index("asymptotic")}


def settled(fine, coarse, control: AccuracyControl) -> bool:
    """Whether the refinement ``fine`` of the run ``coarse`` settles the point: F̄max moved
    by at most ``control.tolerance`` and the number of impacts held.

    An agreement between runs with different impact sequences is a coincidence (measured:
    plate ζ = 108, λ = 0.0095 agreed to 3.2e-4 at 3 and 5 impacts while the converged value
    lay 1.2e-3 away), so it does not count.
    """
    return (abs(fine.fmax_normalised - coarse.fmax_normalised) <= control.tolerance
            and fine.impacts == coarse.impacts)


def perturbed_runs(run: Callable, settings, perturbation: float) -> list:
    """The five runs that measure a sensitive point's spread, perturbed from ``settings``:
    cut-off × (1 ± p), step × (1 − p), ζ × (1 ± p), p = ``perturbation`` [-] (in this order;
    ``run`` as in :func:`controlled_point`)."""
    p = perturbation
    return [
        run(replace(settings, cutoff_ratio=settings.cutoff_ratio * (1.0 + p)), 1.0),
        run(replace(settings, cutoff_ratio=settings.cutoff_ratio * (1.0 - p)), 1.0),
        run(replace(settings, step_scale=settings.step_scale * (1.0 - p)), 1.0),
        run(settings, 1.0 + p),
        run(settings, 1.0 - p),
    ]


def controlled_point(run: Callable, settings, control: AccuracyControl) -> dict:
    """Solve one point to the tolerance, or mark it, with its error.

    Parameters
    ----------
    run : callable
        ``run(settings, zeta_factor) -> result``: the point solved with the given
        :class:`~impactmaps.solvers.modal_settings.ModalSettings` at ζ × ``zeta_factor`` (an
        ImpactResult, or any object with ``fmax_normalised``, ``impacts`` and
        ``normalised_summary()``).
    settings : ModalSettings
        The base settings of the sweep.
    control : AccuracyControl

    Returns
    -------
    dict
        The normalised scalars of the retained run (``normalised_summary``) plus
        ``fmax_error``, ``fmax_low``, ``fmax_high`` and the ``status`` code; the error of a
        settled point is the change as measured, without its floor (:func:`stated_row`).
    """
    results = [run(settings, 1.0)]
    level = settings
    for count in range(1, int(control.max_refinements) + 1):
        level = level.refined()
        results.append(run(level, 1.0))
        if settled(results[-1], results[-2], control):
            fine = results[-1].fmax_normalised
            change = abs(fine - results[-2].fmax_normalised)
            return _row(results[-1], "converged" if count == 1 else "refined",
                        change, fine - change, fine + change)
    # the perturbations of cut-off, step and ζ are made from the base settings, and the
    # finest value is widened by at least the tolerance. Measured (validation/
    # sensitive_bands.py) at 70 random sensitive points each of the SS Euler beam and the
    # Kirchhoff plate against a third refinement: this band held it at 138 of 140 (misses
    # 5.6e-3, 6.4e-4); perturbing the finest level instead, without the widening (the band
    # before 2026-11-24), at 132 — at 16× the cost of the perturbed runs (4× the modes,
    # 1/4 of the step)
    perturbed = perturbed_runs(run, settings, control.perturbation)
    finest = results[-1].fmax_normalised
    widening = max(abs(finest - results[-2].fmax_normalised), control.tolerance)
    values = [r.fmax_normalised for r in results + perturbed] + [finest - widening, finest + widening]
    low, high = min(values), max(values)
    return _row(results[-1], "sensitive", 0.5 * (high - low), low, high)


# -- the status of an answer read between map points (a lookup's) ------------------------------

#: Severity of a status when map points (or slenderness members) are combined (worst wins);
#: ``interpolated`` is a lookup's own status (:func:`answer_status`), never a point's.
SEVERITY = {"asymptotic": 0, "converged": 0, "refined": 1, "interpolated": 2, "sensitive": 3, "unresolved": 4}
#: The status of each severity.
BY_SEVERITY = np.array(["converged", "refined", "interpolated", "sensitive", "unresolved"])
#: Severity of each status code (:data:`STATUSES`).
CODE_SEVERITY = np.array([SEVERITY[name] for name in STATUSES])
#: The map points' refinement tolerance (``AccuracyControl().tolerance``): a lookup whose
#: band is wider is ``interpolated``, even where every point around it converged.
BAND_TOLERANCE = AccuracyControl().tolerance


def answer_status(point_status, band):
    """The status of an interpolated answer from its map points' worst status and its band.

    ``interpolated`` where the points converged (``converged``, ``refined``) but the band
    — their own error plus the interpolation (or slenderness) error between them — is wider
    than :data:`BAND_TOLERANCE`: the points are right, the value between them is known only
    to ± the band (near a re-impact kink of F̄max the interpolation errs by up to a few
    1e-2). Otherwise the points' status. Scalars give a ``str``, arrays an array.
    """
    status = np.asarray(point_status)
    widened = ((status == "converged") | (status == "refined")) & (np.asarray(band) > BAND_TOLERANCE)
    out = np.where(widened, "interpolated", status)
    return out.item() if out.ndim == 0 else out


def corner_status(corner_codes, band):
    """The status of an answer read between map points: the worst of the points' statuses
    (``corner_codes``: one array of status codes of :data:`STATUSES`
    per corner around the answers), ``interpolated`` where the ``band`` makes it so
    (:func:`answer_status`)."""
    worst = np.max(CODE_SEVERITY[np.asarray(corner_codes)], axis=0)
    return answer_status(BY_SEVERITY[worst], band)


#: What a lookup's status means for its number, where that needs saying.
_STATUS_NOTES = {
    "interpolated": "the map points around this one converged, but between them F̄max is known only to "
                    "± fmax_error (interpolation across the map's kinks or curvature); a simulation computes "
                    "it to 1e-3 (`impactmaps point` for the linear law, `impactmaps simulate` on a case file for "
                    "any law)",
    "sensitive": "no converged value: re-impacts whose order flips with any change of the model; read the band "
                 "(± fmax_error), not the number",
}


def status_notes(status) -> dict:
    """``{"status_note": text}`` for a status whose number needs a word (``interpolated``,
    ``sensitive``), else ``{}``; what the command line prints beside a lookup's status."""
    note = _STATUS_NOTES.get(str(status)) if np.ndim(status) == 0 else None
    return {"status_note": note} if note else {}
