"""Rows of the recorded history of the modal impact integrators (numba).

A history is a :class:`HistoryRows`: an (n_records, 8) table — t, F, α, w_i, v_i, w_t, v_t,
E_structure — grown by doubling up to its row cap; :func:`record_row` appends the state at
one instant, or nothing once the cap is reached (the integrator then stops the run).
Shared by the sampled scheme (:mod:`impactmaps.solvers.integrator.exact_step`) and the exact linear
contact phase (:mod:`impactmaps.solvers.integrator.coupled_contact`).
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

__all__ = ["HISTORY_WIDTH", "HistoryRows", "new_history", "record_row", "structure_energy", "zeros_matrix"]

#: Columns of the recorded history.
HISTORY_WIDTH = 8


class HistoryRows(NamedTuple):
    """A history being recorded: ``table`` (rows × :data:`HISTORY_WIDTH`, float64) holds at
    most ``cap`` rows."""

    table: np.ndarray
    cap: int


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def zeros_matrix(rows, cols):
    """A (rows, cols) float64 array of zeros, filled by a loop: ``np.zeros`` of a 2-D shape
    compiles three overloads more than ``np.empty``, again in every kernel that types it
    (the solvers' 2-D zeros all come from here). Callers pass int64 values, not literals
    (``np.int64(2)``, not ``2``): each literal would compile a specialisation of its own."""
    out = np.empty((rows, cols))
    for i in range(rows):
        for j in range(cols):
            out[i, j] = 0.0
    return out


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def new_history(rows, cap):
    """An empty :class:`HistoryRows` of ``min(rows, cap)`` zero rows, at most ``cap`` rows."""
    return HistoryRows(zeros_matrix(max(min(rows, cap), 1), np.int64(HISTORY_WIDTH)), cap)


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def structure_energy(omega, q, v):
    energy = 0.0
    for j in range(q.shape[0]):
        energy += 0.5 * (v[j] * v[j] + omega[j] * omega[j] * q[j] * q[j])
    return energy


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _record_state(history, rec, t, force, wi, vi, residual, omega, phi, q, v):
    """Write the state at time t [s] into row ``rec`` of the history."""
    wt = residual * force
    vt = 0.0
    for j in range(q.shape[0]):
        wt += phi[j] * q[j]
        vt += phi[j] * v[j]
    history[rec, 0] = t
    history[rec, 1] = force
    history[rec, 2] = wi - wt
    history[rec, 3] = wi
    history[rec, 4] = vi
    history[rec, 5] = wt
    history[rec, 6] = vt
    history[rec, 7] = structure_energy(omega, q, v) + 0.5 * residual * force * force


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def _grown(history, cap):
    """The history array with twice the rows, at most ``cap`` (the new ones zero)."""
    grown = zeros_matrix(min(2 * history.shape[0], cap), np.int64(HISTORY_WIDTH))
    for row in range(history.shape[0]):  # element loops: a slice assignment compiles for seconds
        for column in range(HISTORY_WIDTH):
            grown[row, column] = history[row, column]
    return grown


@numba.njit(cache=True, no_cpython_wrapper=True, no_cfunc_wrapper=True)
def record_row(history, rec, t, force, wi, vi, residual, omega, phi, q, v):
    """Append the state at time t [s] as row ``rec`` of the :class:`HistoryRows` (growing its
    table when full), nothing once it holds its ``cap`` rows; returns the history and the
    next row index (``cap`` at most)."""
    if rec >= history.cap:
        return history, rec
    if rec == history.table.shape[0]:
        history = HistoryRows(_grown(history.table, history.cap), history.cap)
    _record_state(history.table, rec, t, force, wi, vi, residual, omega, phi, q, v)
    return history, rec + 1
