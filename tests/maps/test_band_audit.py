"""The stated error of map points and lookups covers the measured error (issue 40 item 10).

Reads the committed output of ``validation/band_audit.py`` (random converged points per
family against references four refinement levels above the base) and checks, with the
floors the code states now (:func:`impactmaps.maps.family.accuracy.stated_error`), that
``fmax_error`` covers the error at ≥ 99 % of the points of every family, and the lookup
bands at ≥ 99 % of the lookups.
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from impactmaps.maps.family.accuracy import ERROR_FLOOR, REIMPACT_ERROR_FLOOR, STATUSES, stated_error

from ..helpers import ROOT

AUDIT = ROOT / "validation" / "band_audit.csv"
FAMILIES = ("beam-ss-euler", "beam-ss-timoshenko-s20", "plate-ssss-kirchhoff", "plate-ssss-mindlin-s20")


@pytest.fixture(scope="module")
def audit():
    frame = pd.read_csv(AUDIT)
    return frame[frame["reference"].notna()]


@pytest.mark.parametrize("family", FAMILIES)
def test_fmax_error_covers_the_error_at_99_percent_of_converged_points(audit, family):
    part = audit[audit.family == family]
    assert len(part) >= 50, f"{family}: only {len(part)} audited points"
    codes = part["status"].map(STATUSES.index).to_numpy()
    stated = stated_error(part["change"].to_numpy(), codes, part["impacts"].to_numpy())
    error = np.abs(part["fmax"] - part["reference"]).to_numpy()
    assert np.mean(error <= stated) >= 0.99, (family, int(np.sum(error > stated)), len(part))


def test_lookup_bands_cover_the_error_at_99_percent(audit):
    looked = audit[audit["lookup_status"].isin(["converged", "refined", "interpolated"])]
    assert len(looked) >= 200
    inside = np.abs(looked["lookup"] - looked["reference"]) <= looked["lookup_band"]
    assert inside.mean() >= 0.99, int((~inside).sum())


def test_stated_error_is_idempotent_and_floors_only_settled_points():
    converged, sensitive = STATUSES.index("converged"), STATUSES.index("sensitive")
    once = stated_error(np.array([0.0, 5e-4, 3e-3, 1e-5]), np.array([converged, converged, converged, sensitive]),
                        np.array([1, 2, 1, 1]))
    assert once.tolist() == [ERROR_FLOOR, REIMPACT_ERROR_FLOOR, 3e-3, 1e-5]
    assert stated_error(once, np.array([converged] * 3 + [sensitive]), np.array([1, 2, 1, 1])).tolist() == once.tolist()
    assert stated_error(1e-6, converged) == ERROR_FLOOR


def test_a_shipped_map_is_read_with_the_floor():
    """The shipped maps store the bare change (built before the floors): the reader floors it."""
    from impactmaps import lookup

    found = lookup(10.0, 0.01, kind="beam", theory="euler")
    assert found.status in ("converged", "refined", "interpolated")
    assert found.fmax_error >= ERROR_FLOOR


def test_a_point_stores_the_measured_change_and_states_it_with_the_floor():
    """A converged point stores the change its refinement measured (the same bits as a shipped
    result computed before the floors); :func:`stated_row` (the ``point`` command) states it with
    its floor, F̄max ∓ the stated error as its low and high; a sensitive point is left as stored."""
    from impactmaps.maps.family.accuracy import AccuracyControl, controlled_point, stated_row
    from impactmaps.solvers.modal_settings import ModalSettings

    class Run:
        def __init__(self, value, impacts):
            self.fmax_normalised, self.impacts = value, impacts

        def normalised_summary(self):
            return {"fmax_normalised": self.fmax_normalised, "impacts": self.impacts}

    for impacts, floor in ((1, ERROR_FLOOR), (2, REIMPACT_ERROR_FLOOR)):
        row = controlled_point(lambda settings, _factor: Run(0.5 + 1e-5 * (settings.cutoff_ratio > 40.0), impacts),
                               ModalSettings(), AccuracyControl())
        assert STATUSES[row["status"]] == "converged"
        assert row["fmax_error"] == pytest.approx(1e-5, rel=1e-9)
        assert row["fmax_low"] == row["fmax_normalised"] - row["fmax_error"]
        told = stated_row(row)
        assert told["fmax_error"] == floor
        fmax = row["fmax_normalised"]
        assert (told["fmax_low"], told["fmax_high"]) == (fmax - floor, fmax + floor)
        assert told["fmax_normalised"] == row["fmax_normalised"] and stated_row(told) == told
    sensitive = {"fmax_normalised": 0.5, "fmax_error": 1e-5, "fmax_low": 0.4, "fmax_high": 0.6,
                 "status": STATUSES.index("sensitive"), "impacts": 3}
    assert stated_row(sensitive) == sensitive
