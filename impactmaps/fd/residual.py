"""The permanent (residual) state of the finite-difference beam after an impact:
the final state unloaded elastically, ``w_res = w − K_e⁻¹ f_int(w)``.
"""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import scipy.linalg

__all__ = ["residual_state"]


def residual_state(beam, grid, curvature, state):
    """Per-node residual state of the final ``state`` at ``curvature`` [1/m].

    Returns a DataFrame ``x_m, final_deflection_m, permanent_deflection_m,
    residual_curvature_1_m, max_plastic_strain, plastic_work_J_m``; warns if the elastic
    unloading would re-yield a layer.
    """
    n = grid.n_nodes
    w = state["w"]
    section = beam.section
    if beam.plastic:
        moment = section.moment(state["stress"]) * (grid.section_weight > 0)
    else:
        moment = -beam.bending_stiffness * curvature * (grid.section_weight > 0)
    q = grid.section_weight * moment / grid.dx
    f_int = np.zeros(n)
    f_int[:-1] -= q[1:] * grid.stencil[0, 1:]
    f_int -= q * grid.stencil[1]
    f_int[1:] -= q[:-1] * grid.stencil[2, :-1]
    free = grid.free
    correction = np.zeros(n)
    rigid_modes = not ((grid.constrained[0] and grid.constrained[-1]) or "cc" in beam.supports)
    if rigid_modes:  # e.g. free–free or ss–free: minimum-norm correction (dense, rare)
        k_free = grid.stiffness_dense()[np.ix_(free, free)]
        correction[free] = np.linalg.lstsq(k_free, f_int[free], rcond=None)[0]
    else:  # K_e is pentadiagonal SPD: banded Cholesky with the supports as identity rows
        band = grid.stiffness_banded.copy()
        for m in np.flatnonzero(grid.constrained):
            band[2, m] = 1.0
            band[1, m] = 0.0
            band[0, m] = 0.0
            if m + 1 < n:
                band[1, m + 1] = 0.0
            if m + 2 < n:
                band[0, m + 2] = 0.0
        rhs = np.where(grid.constrained, 0.0, f_int)
        correction = scipy.linalg.solveh_banded(band, rhs)
    residual_w = w - correction
    stencil = grid.stencil
    residual_k = stencil[1] * residual_w
    residual_k[1:] += stencil[0, 1:] * residual_w[:-1]
    residual_k[:-1] += stencil[2, :-1] * residual_w[1:]
    residual_k /= grid.dx**2
    if beam.plastic:  # check that the unloading stays elastic
        dk = residual_k - curvature
        unloaded = state["stress"] - beam.youngs_modulus * np.outer(dk, section.layer_positions)
        relative = np.abs(unloaded - state["back"]) - beam.yield_strength
        if np.max(relative[grid.section_weight > 0], initial=-1.0) > 1e-6 * beam.yield_strength:
            warnings.warn(
                "elastic unloading to the permanent deflection re-yields some layers; "
                "permanent_beam_deflection is approximate", stacklevel=3)
    max_plastic = np.max(np.abs(state["plastic_strain"]), axis=1)
    return pd.DataFrame({
        "x_m": np.linspace(0.0, beam.length, n),
        "final_deflection_m": w,
        "permanent_deflection_m": residual_w,
        "residual_curvature_1_m": residual_k,
        "max_plastic_strain": max_plastic,
        "plastic_work_J_m": state["plastic_work_node"],
    })
