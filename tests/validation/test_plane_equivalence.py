"""validation/plane_equivalence.py counts what a change of the plane moves: F̄max beyond the
old point's stated error or band, status and impact changes (synthetic planes, no solving)."""

from __future__ import annotations

import numpy as np

from ..helpers import repository_module

plane_equivalence = repository_module("validation/plane_equivalence.py")


def _plane(path, fmax, status, impacts):
    shape = (1, 3)
    arrays = {"zeta": np.array([0.1, 1.0, 10.0]), "lambda_": np.array([0.5])}
    for name in plane_equivalence.STRUCTURES:
        values = {"fmax_normalised": np.array([fmax]), "fmax_error": np.full(shape, 1e-4),
                  "fmax_low": np.array([fmax]) - 1e-4, "fmax_high": np.array([fmax]) + 1e-4,
                  "status": np.array([status]), "method": np.zeros(shape), "impacts": np.array([impacts]),
                  "n_modes": np.full(shape, 4.0), "contact_time_normalised": np.ones(shape),
                  "energy_transferred_fraction": np.ones(shape), "cpu": np.full(shape, 0.01)}
        arrays |= {f"{name}/{key}": np.asarray(value, dtype=float) for key, value in values.items()}
    np.savez(path, **arrays)
    return str(path)


def test_compare_counts_points_beyond_their_stated_error(tmp_path):
    old = _plane(tmp_path / "old.npz", [0.5, 0.6, 0.7], [0, 0, 2], [1, 1, 5])
    new = _plane(tmp_path / "new.npz", [0.5, 0.60005, 0.7003], [0, 1, 2], [1, 1, 6])
    # per structure: the second point moved within its error (status changed), the third beyond it
    assert plane_equivalence.compare(old, new, str(tmp_path / "summary"), "a title") == 2
    text = (tmp_path / "summary.md").read_text()
    assert "a title" in text and "**2**" in text
    rows = (tmp_path / "summary.csv").read_text().splitlines()
    assert len(rows) == 1 + 2 * 2  # header, and per structure the status change and the point beyond
    assert plane_equivalence.compare(old, old, None) == 0
