"""Rows of the recorded history of the modal impact integrators (numba).

A history is an (n_records, 8) array — t, F, α, w_i, v_i, w_t, v_t, E_structure — grown
by doubling; :func:`record_row` appends the state at one instant. Shared by the sampled
scheme (:mod:`impactmaps.solvers.exact_step`) and the exact linear contact phase
(:mod:`impactmaps.solvers.coupled_contact`).
"""

from __future__ import annotations

import numba
import numpy as np

__all__ = ["HISTORY_WIDTH", "record_row", "structure_energy"]

#: Columns of the recorded history.
HISTORY_WIDTH = 8


@numba.njit(cache=True)
def structure_energy(omega, q, v):
    energy = 0.0
    for j in range(q.shape[0]):
        energy += 0.5 * (v[j] * v[j] + omega[j] * omega[j] * q[j] * q[j])
    return energy


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def _grown(history):
    """The history array with twice the rows (the new ones zero)."""
    grown = np.zeros((2 * history.shape[0], HISTORY_WIDTH))
    for row in range(history.shape[0]):  # element loops: a slice assignment compiles for seconds
        for column in range(HISTORY_WIDTH):
            grown[row, column] = history[row, column]
    return grown


@numba.njit(cache=True)
def record_row(history, rec, t, force, wi, vi, residual, omega, phi, q, v):
    """Append the state at time t [s] as row ``rec`` (growing the array when full);
    returns the history array and the next row index."""
    if rec == history.shape[0]:
        history = _grown(history)
    _record_state(history, rec, t, force, wi, vi, residual, omega, phi, q, v)
    return history, rec + 1
