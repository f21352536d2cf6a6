"""Run a case with the solver it asks for, summarise it, write and read its outputs."""

from __future__ import annotations

import json
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd

from ..jsonio import dumps, plain
from ..solvers.modal import simulate
from ..solvers.mode_budget import ModeBudgetError
from ..result import ImpactResult
from .._files import written_atomically
from .._checks import ModelValidityWarning
from ..validity import case_warnings
from .case import Case
from .numbers import case_numbers

__all__ = ["run_case", "case_summary", "write_case_outputs",
           "read_case_outputs"]


def case_summary(case: Case, result: ImpactResult) -> dict:
    """The JSON-ready summary of a run of ``case`` (keys carry their units).

    ``result.summary()`` plus ``max_deflection_m`` [m], the numbers of
    :func:`impactmaps.cases.numbers.case_numbers` in the vocabulary of the law's maps,
    ``model_warnings`` (:func:`impactmaps.validity.case_warnings`) and the case identity;
    NaN becomes ``None`` (keys: docs/output_keys.rst).
    """
    summary = dict(result.summary())
    if result.history is not None and len(result.history):
        deflection = result.history["target_displacement_m"].to_numpy()
        summary["max_deflection_m"] = float(np.max(np.abs(deflection)))
    else:
        moved = getattr(getattr(result, "details", None), "max_target_displacement", None)
        summary["max_deflection_m"] = None if moved is None else float(moved)
    numbers = case_numbers(case)
    if numbers["vocabulary"] != "linear":  # the solver's own basis, under explicit names
        for key in ("fmax_normalised", "contact_time_normalised"):
            if key in summary:
                summary[f"{key}_reference"] = summary.pop(key)
    summary["fmax_normalised"] = float(result.peak_force) / numbers["force_scale_N"]
    summary["contact_time_normalised"] = float(result.total_contact_time) / numbers["time_scale_s"]
    summary.update(numbers)
    summary["model_warnings"] = case_warnings(case, result)
    summary.update({
        "case": case.name,
        "target_type": case.target_type,
        "law": case.law_name,
        "solver": case.solver_kind,
        "end_time_s": float(result.end_time),
    })
    return _with_null_notes(plain(summary), case, result)


def _null_notes(case: Case, result: ImpactResult) -> dict:
    """Why a summary key is ``null``, for the keys whose reason is known."""
    in_contact = ("the run ends with the sphere still in contact (time limit reached): it has not left the "
                  "target; a longer [solver] duration gives it") if result.time_limit_reached else \
        "not defined for this run"
    halfspace = "a half-space has no structure stiffness (K_st is infinite)"
    return {
        **dict.fromkeys(("restitution", "rebound_velocity_m_s", "rebound_kinetic_energy_J", "energy_loss_J",
                         "energy_transferred_J", "permanent_indentation_m", "first_contact_duration_s"),
                        in_contact),
        "beta": f"the {case.law_name} law has no yield indentation: β is a number of the elastic-plastic laws",
        "zeta": halfspace, "lambda": halfspace, "static_stiffness_N_m": halfspace,
        "zeta_linearised": halfspace, "lambda_linearised": halfspace,
        "converged": "not checked ([solver] check_convergence = false; a finite-difference run then reruns on "
                     "twice the [fd] n_elements)" if case.solver_kind == "fd" else ("not checked: answered by the infinite-structure asymptote, exact until the first "
                      "reflection returns") if result.method == "infinite-structure-asymptote" else
        "not checked ([solver] check_convergence = false)",
        "max_deflection_m": "no history: the run gives scalars only",
    }


def _with_null_notes(summary: dict, case: Case, result: ImpactResult) -> dict:
    """``summary`` with a ``<key>_note`` beside each top-level ``null`` saying why."""
    notes = _null_notes(case, result)
    out = {}
    for key, value in summary.items():
        out[key] = value
        if value is None and f"{key}_note" not in summary:
            out[f"{key}_note"] = notes.get(key, "does not exist for this run")
    return out


def _run_fd(case: Case) -> ImpactResult:
    """The finite-difference run of ``case``; with ``[solver] check_convergence`` also checked
    against twice the elements (``converged`` set against ``[solver] tolerance``).
    """
    from ..fd import simulate_fd
    from ..solvers.modal_settings import ConvergenceWarning

    settings = replace(case.fd_settings, duration=case.duration)
    result = simulate_fd(case.target, case.law, case.impactor_mass, case.velocity,
                         settings=settings, material=case.target_material)
    if not case.settings.check_convergence:
        return result
    elements = 2 * int(result.settings["beam"].n_elements)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the fine run's own warnings say nothing new
        fine = simulate_fd(case.target, case.law, case.impactor_mass, case.velocity,
                           settings=replace(settings, n_elements=elements), material=case.target_material)
    change, tolerance = abs(fine.fmax_normalised - result.fmax_normalised), case.settings.tolerance
    if change <= tolerance:
        return replace(result, converged=True)
    note = (f"F̄max changed by {change:.2e} (> tolerance {tolerance:g}) when the grid was refined to {elements} "
            "elements; the result is not converged (a late re-impact needs a finer [fd] n_elements)")
    warnings.warn(note, ConvergenceWarning, stacklevel=3)
    return replace(result, converged=False, convergence_note=note)


def run_case(case: Case) -> tuple[ImpactResult, dict]:
    """Run the solver ``case.solver_kind`` asks for; returns the full ``result`` (with
    histories) and its :func:`case_summary` (each ``model_warnings`` entry also issued as a
    :class:`~impactmaps._checks.ModelValidityWarning`).
    """
    if not isinstance(case, Case):
        raise ValueError(f"case = {case!r} is not a Case (build one with load_case or parse_case)")
    if case.solver_kind == "fd":
        result = _run_fd(case)
    else:
        try:
            with warnings.catch_warnings():  # the case's own checks below say all of them, once
                warnings.simplefilter("ignore", ModelValidityWarning)
                warnings.filterwarnings("ignore", message="contact radius .* exceeds half the plate thickness")
                result = simulate(case.target, case.law, case.impactor_mass, case.velocity,
                                  settings=case.settings, record=True, time_step=case.time_step)
        except ModeBudgetError as error:
            point = "impact_point" if case.target_type == "plate" else "impact_position"
            raise ValueError(
                f"impactor.mass = {case.impactor_mass:.6g} kg is invalid for this target: {error.reason}; "
                f"valid range: impactor.mass ≥ about {error.lightest_mass:.4g} kg (contact frequency ≤ "
                f"{error.highest_frequency:.4g} rad/s), or a target.{point} farther from the boundary"
            ) from None
    summary = case_summary(case, result)
    for message in summary["model_warnings"]:
        warnings.warn(message, ModelValidityWarning, stacklevel=2)
    return result, summary


def write_case_outputs(case: Case, result: ImpactResult, out_dir) -> dict:
    """Write the histories, the summary and a copy of the case file of a run of ``case`` to
    ``out_dir`` (created if needed); returns ``{"history", "summary", "case"}`` paths (with
    ``"history_normalised"`` when ``output.normalised``; no history when the result has none).
    """
    if not isinstance(case, Case):
        raise ValueError(f"case = {case!r} is not a Case")
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    paths = {"history": out / "history.csv", "summary": out / "summary.json",
             "case": out / "case.toml"}
    stride = case.output.history_stride
    if result.history is None:
        del paths["history"]
    else:
        with written_atomically(paths["history"]) as part:
            result.history.iloc[::stride].to_csv(part, index=False)
    if case.output.normalised and result.history is not None:
        paths["history_normalised"] = out / "history_normalised.csv"
        with written_atomically(paths["history_normalised"]) as part:
            result.normalised_history().iloc[::stride].to_csv(part, index=False)
    with written_atomically(paths["case"]) as part:
        part.write_text(case.source_text, encoding="utf-8")
    with written_atomically(paths["summary"]) as part:  # last: a study's resume reads it as "done"
        part.write_text(dumps(case_summary(case, result), indent=2) + "\n", encoding="utf-8")
    return paths


def read_case_outputs(out_dir) -> tuple[pd.DataFrame, dict]:
    """Read back ``history.csv`` and ``summary.json`` written by :func:`write_case_outputs`."""
    out = Path(out_dir)
    history = pd.read_csv(out / "history.csv")
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    return history, summary
