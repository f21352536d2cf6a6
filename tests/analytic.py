"""Small systems with known answers, independent of impactmaps.targets.

Closed-form modal bases of a simply supported Euler beam and a simply supported square
Kirchhoff plate struck at the centre, in units where the structure's stiffness and mass
scales are 1. They let the solver tests run without the target modules, so a bug in a
target and a bug in the solver cannot hide each other.
"""

from __future__ import annotations

import numpy as np

from impactmaps.targets.base import ModalBasis

BEAM_STATIC_COMPLIANCE = 1.0 / 48.0  # L³/(48 EI) with L = EI = 1
PLATE_STATIC_COMPLIANCE = 0.01160083977  # centre of SS square plate, a²/D: Navier sum, inner series in closed form


def _truncate(frequencies, participation, static, max_frequency, min_modes):
    order = np.argsort(frequencies, kind="stable")
    frequencies, participation = frequencies[order], participation[order]
    count = max(int(np.count_nonzero(frequencies <= max_frequency)), min_modes)
    keep = slice(0, count)
    retained = np.sum(participation[keep] ** 2 / frequencies[keep] ** 2)
    return ModalBasis(frequencies[keep], participation[keep], max(static - retained, 0.0))


def ss_euler_beam_basis(max_frequency, min_modes=1, max_index=100_000):
    """SS Euler beam, L = EI = ρA = 1, struck at mid-span (odd modes only)."""
    n = np.arange(1, max_index + 1, 2)
    frequencies = (n * np.pi) ** 2
    participation = np.sqrt(2.0) * np.sin(n * np.pi / 2)
    return _truncate(frequencies, participation, BEAM_STATIC_COMPLIANCE, max_frequency, min_modes)


def ss_square_plate_basis(max_frequency, min_modes=1, max_index=801):
    """SS square Kirchhoff plate, a = D = ρh = 1, struck at the centre (odd m, n)."""
    m = np.arange(1, max_index + 1, 2)
    mm, nn = np.meshgrid(m, m, indexing="ij")
    frequencies = (np.pi**2 * (mm**2 + nn**2)).ravel()
    participation = (2.0 * np.sin(mm * np.pi / 2) * np.sin(nn * np.pi / 2)).ravel()
    return _truncate(frequencies, participation, PLATE_STATIC_COMPLIANCE, max_frequency, min_modes)


def ss_beam_impactor(loss_factor, relative_stiffness):
    """(mass, contact stiffness) realising (ζ, λ) on the unit SS Euler beam (spec §4)."""
    stiffness = 48.0 / relative_stiffness
    mass = (4 * np.sqrt(2 * np.pi) * loss_factor) ** (4 / 3) * (1.0 / stiffness) ** (1 / 3)
    return mass, stiffness


def ss_plate_impactor(loss_factor, relative_stiffness):
    """(mass, contact stiffness) realising (ζ, λ) on the unit SS square plate (spec §4)."""
    stiffness = 1.0 / (PLATE_STATIC_COMPLIANCE * relative_stiffness)
    mass = 256 * loss_factor**2 / stiffness
    return mass, stiffness
